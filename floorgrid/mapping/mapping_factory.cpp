#include "floorgrid/mapping/mapping_factory.hpp"

#include <algorithm>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/gaussian_process_mapping.hpp"
#include "floorgrid/mapping/global_transform.hpp"
#include "floorgrid/mapping/piecewise_affine.hpp"
#include "floorgrid/mapping/thin_plate_spline_mapping.hpp"

namespace floorgrid {

const std::vector<std::string>& mapping_model_names() {
  static const std::vector<std::string> names = {"lc", "gt",   "gt-rigid", "gt-affine", "ct",
                                                 "gp", "gpgt", "dt",       "tps",       "auto"};
  return names;
}

std::unique_ptr<PointMapping> make_mapping(const MappingOptions& o) {
  const std::string& m = o.model;
  if (m == "gt" || m == "gt-rigid" || m == "gt-affine") {
    RansacOptions ransac = o.ransac;
    ransac.kind = m == "gt"         ? TransformKind::similarity
                  : m == "gt-rigid" ? TransformKind::rigid
                                    : TransformKind::affine;
    return std::make_unique<GlobalTransformMapping>(o.common, ransac);
  }
  if (m == "lc")
    return std::make_unique<LinearCombinationMapping>(o.common, o.lc);
  if (m == "ct")
    return std::make_unique<LocalTransformsMapping>(o.common, o.ct);
  if (m == "tps")
    return std::make_unique<ThinPlateSplineMapping>(o.common, o.tps);
  if (m == "dt")
    return std::make_unique<PiecewiseAffineMapping>(o.common);
  if (m == "gp" || m == "gpgt") {
    RansacOptions ransac = o.ransac;
    ransac.inlier_threshold = o.gpgt_inlier_threshold;
    return std::make_unique<GaussianProcessMapping>(o.common, o.gp, m == "gpgt", ransac);
  }
  if (m == "auto") {
    // Only the candidates this build knows (the default list names every model).
    MappingOptions a = o;
    std::vector<std::string> known;
    for (const auto& c : a.auto_select.candidates) {
      const auto& names = mapping_model_names();
      if (c != "auto" && std::find(names.begin(), names.end(), c) != names.end()) {
        known.push_back(c);
      }
    }
    a.auto_select.candidates = known;
    return std::make_unique<AutoMapping>(a);
  }
  std::string known;
  for (const auto& n : mapping_model_names())
    known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown model '" + m + "' (known: " + known + ")", {}, 0, "model");
}

}  // namespace floorgrid
