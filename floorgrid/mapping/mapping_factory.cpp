#include "floorgrid/mapping/mapping_factory.hpp"

#include <algorithm>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/global_transform.hpp"

namespace floorgrid {

const std::vector<std::string>& mapping_model_names() {
  static const std::vector<std::string> names = {"lc", "gt", "gt-rigid", "gt-affine", "ct"};
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
  std::string known;
  for (const auto& n : mapping_model_names())
    known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown model '" + m + "' (known: " + known + ")", {}, 0, "model");
}

}  // namespace floorgrid
