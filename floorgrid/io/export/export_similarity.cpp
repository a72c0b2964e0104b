#include "floorgrid/io/export/export_similarity.hpp"

#include <fmt/format.h>

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/mapping/global_transform.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid::io {

namespace {

/// Scale, yaw and reflection of a similarity's linear part.
void decompose(ModelSimilarity& s) {
  const Eigen::Matrix2d A = s.T_grid_plan.topLeftCorner<2, 2>();
  s.reflected = A.determinant() < 0.0;
  s.scale = std::sqrt(std::abs(A.determinant()));
  s.yaw = std::atan2(A(1, 0), A(0, 0));
}

}  // namespace

const PointMapping& exported_model(const PointMapping& model) {
  if (const auto* chooser = dynamic_cast<const AutoMapping*>(&model))
    return exported_model(chooser->chosen());
  return model;
}

bool model_is_affine(const PointMapping& model) {
  return dynamic_cast<const GlobalTransformMapping*>(&exported_model(model)) != nullptr;
}

ModelSimilarity model_similarity(const PointMapping& model,
                                 const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) {
  const PointMapping& m = exported_model(model);
  ModelSimilarity s;
  if (const auto* gt = dynamic_cast<const GlobalTransformMapping*>(&m);
      gt && (m.name() == "gt" || m.name() == "gt-rigid")) {
    s.T_grid_plan = gt->T_grid_plan();
    s.exact = true;
    s.source = fmt::format("exact: the {} model's T_grid_plan", m.name());
    decompose(s);
    return s;
  }
  if (points_in_plan.cols() < 2) {
    throw InputError(
        fmt::format("the {} model is not a similarity: its least-squares similarity needs at "
                    "least 2 plan points (got {})",
                    m.name(), points_in_plan.cols()),
        {}, 0, "points");
  }
  const Eigen::Matrix2Xd mapped = m.forward_batch(points_in_plan);
  TransformEstimationOptions options;
  options.kind = TransformKind::similarity;
  const TransformEstimate e = estimate_transform(points_in_plan, mapped, options);
  s.T_grid_plan = e.T_grid_plan;
  s.rms_m = e.rms;
  s.points = static_cast<std::size_t>(points_in_plan.cols());
  s.source = fmt::format(
      "least-squares similarity of the {} model over {} plan points, rms residual {:.4f} m",
      m.name(), s.points, s.rms_m);
  decompose(s);
  if (!s.T_grid_plan.allFinite() || !std::isfinite(s.rms_m) || !(s.scale > 0.0)) {
    throw InputError(fmt::format("the {} model's least-squares similarity is not finite or has "
                                 "no scale (the model maps the plan to non-finite points): "
                                 "nothing is written",
                                 m.name()),
                     {}, 0, "model");
  }
  return s;
}

}  // namespace floorgrid::io
