#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/simulation/arc_bend.hpp"
#include "floorgrid/simulation/room_rotation.hpp"

namespace floorgrid {

/// The simulator's ground-truth distortion from the metric world to the SLAM-like gridmap
/// (SPEC "Synthetic datasets"): first the room rotation (in world coordinates), then the bend of
/// the long axis (also in world coordinates), then the rigid transform into the grid frame.
struct WarpParams {
  Pose2 T_grid_world;                ///< the rigid part: world frame into grid frame
  ArcBend bend;                      ///< the smooth bend; curvature 0 for none
  std::optional<RoomRotation> room;  ///< the rotated room, if any
};

/// Settings of the Newton iterations that invert the warp.
struct InverseOptions {
  double tolerance = 1e-10;  ///< metres: stop once |world_to_grid(p) - target| is at most this
  int max_iterations = 50;   ///< Newton steps at most
};

/// One inverted point.
struct InverseResult {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< the world point found, metres
  int iterations = 0;  ///< Newton steps taken (0: the start was already within tolerance)
  /// |world_to_grid(point) - target|, metres.
  double residual = std::numeric_limits<double>::infinity();
  bool converged = false;  ///< residual <= tolerance
};

/// Many inverted points.
struct BatchInverseResult {
  Eigen::Matrix2Xd points;  ///< the world points found, one per column, metres
  int max_iterations = 0;   ///< the most Newton steps any point took
  double max_residual = 0;  ///< the largest residual, metres
  int failures = 0;         ///< points that did not converge
  bool converged = true;    ///< every point converged
};

/// One inverted pose.
struct PoseInverseResult {
  Pose2 pose;                                                 ///< the pose in the world frame
  int iterations = 0;                                         ///< Newton steps for its position
  double residual = std::numeric_limits<double>::infinity();  ///< of its position, metres
  bool converged = false;                                     ///< the position converged
};

/// The exact warp world -> grid, T_grid_world ∘ bend ∘ room, with its analytic Jacobian and its
/// inverse by Newton iterations. Pure and deterministic.
///
/// The warp is one-to-one where the bend is (1 - k v > 0 and |k u| < pi in axis coordinates)
/// and the room rotation keeps det J > 0 (check with min_jacobian_determinant); the constructor
/// checks only that the parameters are finite and well-formed. The batch functions have their own
/// names because overloads on Eigen::Vector2d and Eigen::Matrix2Xd are ambiguous for Eigen
/// expressions and braced lists.
class SimulatedWarp {
 public:
  /// Takes the parameters; InputError naming the field ("warp.T_grid_world", "bend.curvature",
  /// "bend.axis_origin", "bend.axis_angle", or as validate_room_rotation) when one is not finite
  /// or the room is malformed.
  explicit SimulatedWarp(WarpParams params);

  /// The parameters.
  const WarpParams& params() const { return params_; }

  /// Maps a world point into the grid frame, metres.
  Eigen::Vector2d world_to_grid(const Eigen::Vector2d& point_in_world) const;
  /// Maps each column of `points_in_world` into the grid frame.
  Eigen::Matrix2Xd world_to_grid_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_world) const;

  /// J_grid_world: d world_to_grid / d point at `point_in_world`, analytic (chain rule over the
  /// three parts).
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_world) const;

  /// The world point that maps to `point_in_grid`: starts from the inverse of the rigid part and
  /// the exact inverse of the bend, then takes Newton steps on the whole forward map with the
  /// analytic Jacobian (halving a step that would not reduce the residual). Non-convergence is
  /// reported in the result, not thrown.
  InverseResult grid_to_world(const Eigen::Vector2d& point_in_grid,
                              const InverseOptions& options = {}) const;
  /// grid_to_world for each column of `points_in_grid`.
  BatchInverseResult grid_to_world_batch(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                         const InverseOptions& options = {}) const;

  /// Maps a pose: its position through world_to_grid, its heading as the direction
  /// (cos θ, sin θ) mapped by the Jacobian at the position.
  Pose2 pose_world_to_grid(const Pose2& pose_in_world) const;
  /// The inverse of pose_world_to_grid: the position by grid_to_world, the heading through the
  /// inverse Jacobian at the world position found.
  PoseInverseResult pose_grid_to_world(const Pose2& pose_in_grid,
                                       const InverseOptions& options = {}) const;

 private:
  WarpParams params_;
};

}  // namespace floorgrid
