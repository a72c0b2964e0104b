#include "floorgrid/simulation/plan_truth.hpp"

#include <cmath>
#include <string>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

PlanTruth::PlanTruth(WarpParams warp, double plan_scale)
    : warp_(std::move(warp)), plan_scale_(plan_scale) {
  if (!(plan_scale > 0.0) || !std::isfinite(plan_scale)) {
    throw InputError("must be a positive number (got " + std::to_string(plan_scale) + ")", {}, 0,
                     "plan.scale");
  }
}

Eigen::Vector2d PlanTruth::plan_to_grid(const Eigen::Vector2d& point_in_plan) const {
  return warp_.world_to_grid(point_in_plan / plan_scale_);
}

Eigen::Matrix2Xd PlanTruth::plan_to_grid_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const {
  return warp_.world_to_grid_batch(points_in_plan / plan_scale_);
}

Eigen::Matrix2d PlanTruth::jacobian(const Eigen::Vector2d& point_in_plan) const {
  return warp_.jacobian(point_in_plan / plan_scale_) / plan_scale_;
}

InverseResult PlanTruth::grid_to_plan(const Eigen::Vector2d& point_in_grid,
                                      const InverseOptions& options) const {
  InverseResult result = warp_.grid_to_world(point_in_grid, options);
  result.point *= plan_scale_;
  return result;
}

Pose2 PlanTruth::pose_plan_to_grid(const Pose2& pose_in_plan) const {
  return warp_.pose_world_to_grid(
      {pose_in_plan.x / plan_scale_, pose_in_plan.y / plan_scale_, pose_in_plan.theta});
}

void validate_warp_choice(const std::optional<double>& plan_scale,
                          const std::optional<double>& bend,
                          const std::optional<double>& rotation_deg) {
  if (plan_scale && (!std::isfinite(*plan_scale) || *plan_scale < 0.05 || *plan_scale > 20))
    throw InputError("must be a number in [0.05, 20]", "", 0, "plan_scale");
  if (bend && (!std::isfinite(*bend) || *bend < 0.0 || *bend > 20.0))
    throw InputError("must be a number of metres in [0, 20]", "", 0, "bend");
  if (rotation_deg && !std::isfinite(*rotation_deg))
    throw InputError("must be a finite number of degrees", "", 0, "rotation");
}

}  // namespace floorgrid
