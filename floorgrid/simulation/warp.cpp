#include "floorgrid/simulation/warp.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

// Halvings tried before a Newton step is given up as not reducing the residual.
constexpr int kMaxStepHalvings = 30;

void validate_warp_params(const WarpParams& params) {
  const Pose2& T = params.T_grid_world;
  if (!(std::isfinite(T.x) && std::isfinite(T.y) && std::isfinite(T.theta))) {
    throw InputError("must be finite", {}, 0, "warp.T_grid_world");
  }
  if (!std::isfinite(params.bend.curvature)) {
    throw InputError("must be a finite number " + got(params.bend.curvature), {}, 0,
                     "bend.curvature");
  }
  if (!params.bend.axis_origin.allFinite()) {
    throw InputError("must be finite", {}, 0, "bend.axis_origin");
  }
  if (!std::isfinite(params.bend.axis_angle)) {
    throw InputError("must be a finite number " + got(params.bend.axis_angle), {}, 0,
                     "bend.axis_angle");
  }
  if (params.room)
    validate_room_rotation(*params.room);
}

}  // namespace

SimulatedWarp::SimulatedWarp(WarpParams params) : params_(std::move(params)) {
  validate_warp_params(params_);
}

Eigen::Vector2d SimulatedWarp::world_to_grid(const Eigen::Vector2d& point_in_world) const {
  const Eigen::Vector2d turned =
      params_.room ? rotate_room_point(*params_.room, point_in_world) : point_in_world;
  return params_.T_grid_world.transform(bend_point(params_.bend, turned));
}

Eigen::Matrix2Xd SimulatedWarp::world_to_grid_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_world) const {
  Eigen::Matrix2Xd points_in_grid(2, points_in_world.cols());
  for (Eigen::Index i = 0; i < points_in_world.cols(); ++i) {
    points_in_grid.col(i) = world_to_grid(points_in_world.col(i));
  }
  return points_in_grid;
}

Eigen::Matrix2d SimulatedWarp::jacobian(const Eigen::Vector2d& point_in_world) const {
  Eigen::Vector2d turned = point_in_world;
  Eigen::Matrix2d J_turned_world = Eigen::Matrix2d::Identity();
  if (params_.room) {
    turned = rotate_room_point(*params_.room, point_in_world);
    J_turned_world = room_rotation_jacobian(*params_.room, point_in_world);
  }
  return params_.T_grid_world.rotation() * bend_jacobian(params_.bend, turned) * J_turned_world;
}

InverseResult SimulatedWarp::grid_to_world(const Eigen::Vector2d& point_in_grid,
                                           const InverseOptions& options) const {
  InverseResult result;
  // The rigid part and the bend invert exactly; only the room rotation is left to Newton.
  result.point =
      unbend_point(params_.bend, params_.T_grid_world.inverse().transform(point_in_grid));
  Eigen::Vector2d error = world_to_grid(result.point) - point_in_grid;
  result.residual = error.norm();
  while (result.residual > options.tolerance && result.iterations < options.max_iterations) {
    const Eigen::Vector2d step = jacobian(result.point).partialPivLu().solve(error);
    // Halve a step that overshoots, so that a start far from the solution cannot diverge.
    bool reduced = false;
    double scale = 1.0;
    for (int halving = 0; halving <= kMaxStepHalvings && !reduced; ++halving, scale *= 0.5) {
      const Eigen::Vector2d candidate = result.point - scale * step;
      const Eigen::Vector2d candidate_error = world_to_grid(candidate) - point_in_grid;
      if (candidate_error.norm() < result.residual) {
        result.point = candidate;
        error = candidate_error;
        result.residual = candidate_error.norm();
        reduced = true;
      }
    }
    ++result.iterations;
    if (!reduced)
      break;  // stalled: at the limit of floating-point precision, or singular
  }
  result.converged = result.residual <= options.tolerance;
  return result;
}

BatchInverseResult SimulatedWarp::grid_to_world_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid, const InverseOptions& options) const {
  BatchInverseResult batch;
  batch.points.resize(2, points_in_grid.cols());
  for (Eigen::Index i = 0; i < points_in_grid.cols(); ++i) {
    const InverseResult one = grid_to_world(points_in_grid.col(i), options);
    batch.points.col(i) = one.point;
    batch.max_iterations = std::max(batch.max_iterations, one.iterations);
    batch.max_residual = std::max(batch.max_residual, one.residual);
    if (!one.converged)
      ++batch.failures;
  }
  batch.converged = batch.failures == 0;
  return batch;
}

Pose2 SimulatedWarp::pose_world_to_grid(const Pose2& pose_in_world) const {
  const Eigen::Vector2d position = world_to_grid(pose_in_world.translation());
  const Eigen::Vector2d heading =
      jacobian(pose_in_world.translation()) *
      Eigen::Vector2d(std::cos(pose_in_world.theta), std::sin(pose_in_world.theta));
  return {position.x(), position.y(), std::atan2(heading.y(), heading.x())};
}

PoseInverseResult SimulatedWarp::pose_grid_to_world(const Pose2& pose_in_grid,
                                                    const InverseOptions& options) const {
  const InverseResult position = grid_to_world(pose_in_grid.translation(), options);
  const Eigen::Vector2d heading =
      jacobian(position.point)
          .partialPivLu()
          .solve(Eigen::Vector2d(std::cos(pose_in_grid.theta), std::sin(pose_in_grid.theta)));
  PoseInverseResult result;
  result.pose = {position.point.x(), position.point.y(), std::atan2(heading.y(), heading.x())};
  result.iterations = position.iterations;
  result.residual = position.residual;
  result.converged = position.converged;
  return result;
}

}  // namespace floorgrid
