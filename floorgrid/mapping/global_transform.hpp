#pragma once

#include "floorgrid/geometry/ransac.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// The global-transform models `gt` (similarity), `gt-rigid` and `gt-affine` (thesis 3.2, 4.2):
/// RANSAC over minimal samples, then a weighted least-squares refit on the inliers. Works on
/// every pair (no reduction: RANSAC scores on subsets). Inverse and Jacobian are analytic.
/// The inlier threshold is the given one or, unset, adapted to the pairs' noise (see
/// ransac_transform); the model file records the one used (`parameters.ransac`).
class GlobalTransformMapping : public PointMapping {
 public:
  /// A model of the family in `ransac.kind`.
  GlobalTransformMapping(MappingCommonOptions common, RansacOptions ransac);

  std::string name() const override;
  std::size_t min_pairs() const override;
  bool needs_non_collinear() const override { return ransac_.kind == TransformKind::affine; }
  bool reduces_pairs() const override { return false; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;
  InverseMapping inverse(const Eigen::Vector2d& point_in_grid) const override;

  /// The fitted homogeneous transform.
  const Eigen::Matrix3d& T_grid_plan() const { return T_grid_plan_; }
  /// Sets the transform directly (used by models that build on a global transform).
  void set_transform(const Eigen::Matrix3d& T_grid_plan);

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  RansacOptions ransac_;
  std::optional<double> threshold_used_;  // metres: the inlier threshold of the fit
  std::string threshold_source_;          // "given" or "adaptive"
  Eigen::Matrix3d T_grid_plan_ = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d T_plan_grid_ = Eigen::Matrix3d::Identity();
};

/// The model name of a transform family: gt, gt-rigid or gt-affine.
std::string global_transform_model_name(TransformKind kind);

}  // namespace floorgrid
