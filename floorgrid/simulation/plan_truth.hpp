#pragma once

#include <optional>

#include "floorgrid/simulation/warp.hpp"

namespace floorgrid {

/// A synthetic dataset's exact answer to "where does this plan point truly lie on the grid?":
/// the plan is the world scaled by `plan_scale` (plan metres per world metre, the plan's unit
/// error), and the gridmap is the world through the warp, so T(p) = warp(p / plan_scale).
class PlanTruth {
 public:
  /// The warp and the plan's scale (> 0).
  PlanTruth(WarpParams warp, double plan_scale);

  /// The warp world -> grid.
  const SimulatedWarp& warp() const { return warp_; }
  /// Plan metres per world metre.
  double plan_scale() const { return plan_scale_; }

  /// A plan point (plan metres) in the grid frame.
  Eigen::Vector2d plan_to_grid(const Eigen::Vector2d& point_in_plan) const;
  /// Each column mapped.
  Eigen::Matrix2Xd plan_to_grid_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const;
  /// J_grid_plan at a plan point.
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const;
  /// The plan point of a grid point, by the warp's Newton inverse (to 1e-10 m by default);
  /// the result's point is in plan metres.
  InverseResult grid_to_plan(const Eigen::Vector2d& point_in_grid,
                             const InverseOptions& options = {}) const;
  /// A plan pose in the grid frame (heading through the Jacobian).
  Pose2 pose_plan_to_grid(const Pose2& pose_in_plan) const;
  /// A world point in plan metres.
  Eigen::Vector2d world_to_plan(const Eigen::Vector2d& point_in_world) const {
    return point_in_world * plan_scale_;
  }

 private:
  SimulatedWarp warp_;
  double plan_scale_;
};

/// Checks a simulated dataset's chosen plan scale (0.05-20), bend (0-20 m) and rotation
/// (finite degrees), each when given; InputError naming the option otherwise.
void validate_warp_choice(const std::optional<double>& plan_scale,
                          const std::optional<double>& bend,
                          const std::optional<double>& rotation_deg);

}  // namespace floorgrid
