#include "floorgrid/simulation/warp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "tests/simulation/warp_test_support.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A warehouse-sized world [0, 100] x [0, 50] m: a random rigid transform, a bend of 1 m at the
// far end of the axis through the middle, and a 4 x 5 m room turned by 3 degrees.
WarpParams warehouse_warp(Random& random, bool with_room = true) {
  WarpParams params;
  params.T_grid_world = {random.uniform(-30, 30), random.uniform(-30, 30),
                         random.uniform(-std::numbers::pi, std::numbers::pi)};
  params.bend.axis_origin = {0.0, 25.0};
  params.bend.axis_angle = 0.0;
  params.bend.curvature = curvature_for_deviation(1.0, 100.0);
  if (with_room) {
    RoomRotation room;
    room.core = Eigen::AlignedBox2d(Eigen::Vector2d(60, 10), Eigen::Vector2d(64, 15));
    room.center = room.core.center();
    room.angle = 3 * kDegree;
    room.band = 0.8;
    params.room = room;
  }
  return params;
}

Eigen::Matrix2Xd random_points(Random& random, int count, const Eigen::Vector2d& lo,
                               const Eigen::Vector2d& hi) {
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y()));
  }
  return points;
}

TEST(WarpFull, JacobianMatchesCentralDifferences) {
  Random random(31);
  const SimulatedWarp warp(warehouse_warp(random));
  const auto f = [&](const Eigen::Vector2d& p) { return warp.world_to_grid(p); };
  // Over the building, and densely over the rotated room and its band.
  const Eigen::Matrix2Xd spread = random_points(random, 500, {0, 0}, {100, 50});
  const Eigen::Matrix2Xd near_room = random_points(random, 500, {59, 9}, {65, 16});
  double worst = 0;
  for (const Eigen::Matrix2Xd* points : {&spread, &near_room}) {
    for (Eigen::Index i = 0; i < points->cols(); ++i) {
      const Eigen::Vector2d p = points->col(i);
      const Eigen::Matrix2d J = warp.jacobian(p);
      const double error = (J - test::central_difference_jacobian(f, p)).norm() / J.norm();
      EXPECT_LT(error, 1e-6) << "at " << p.transpose();
      worst = std::max(worst, error);
    }
  }
  std::cout << "[ info     ] Jacobian vs central differences: worst relative error " << worst
            << "\n";
}

TEST(WarpFull, RoundTripOfTenThousandPoints) {
  Random random(32);
  const SimulatedWarp warp(warehouse_warp(random));
  for (const bool room_only : {false, true}) {
    const Eigen::Matrix2Xd points_in_world = room_only
                                                 ? random_points(random, 2000, {59, 9}, {65, 16})
                                                 : random_points(random, 10000, {0, 0}, {100, 50});
    const BatchInverseResult inverse =
        warp.grid_to_world_batch(warp.world_to_grid_batch(points_in_world));
    EXPECT_TRUE(inverse.converged);
    EXPECT_EQ(inverse.failures, 0);
    EXPECT_LE(inverse.max_residual, 1e-10);
    const double worst = (inverse.points - points_in_world).colwise().norm().maxCoeff();
    EXPECT_LT(worst, 1e-9);
    EXPECT_LE(inverse.max_iterations, 5);
    std::cout << "[ info     ] " << (room_only ? "2000 points around the room" : "10000 points")
              << ": worst round trip " << worst << " m, max Newton iterations "
              << inverse.max_iterations << "\n";
  }
}

TEST(WarpFull, RigidAndBendInvertWithoutNewton) {
  // Without the room, the start (inverse rigid transform, exact inverse bend) is the answer.
  Random random(33);
  const SimulatedWarp warp(warehouse_warp(random, false));
  const Eigen::Matrix2Xd points_in_world = random_points(random, 1000, {0, 0}, {100, 50});
  const BatchInverseResult inverse =
      warp.grid_to_world_batch(warp.world_to_grid_batch(points_in_world));
  EXPECT_EQ(inverse.max_iterations, 0);
  EXPECT_TRUE(inverse.converged);
  EXPECT_LT((inverse.points - points_in_world).colwise().norm().maxCoeff(), 1e-11);
}

TEST(WarpFull, ComposesRoomThenBendThenRigid) {
  Random random(34);
  const WarpParams params = warehouse_warp(random);
  const SimulatedWarp warp(params);
  // In the core: rotate about the room centre, then the bend, then the rigid transform.
  const Eigen::Vector2d p(61.0, 12.0);
  const Eigen::Vector2d turned =
      params.room->center + rotation_2d(params.room->angle) * (p - params.room->center);
  const Eigen::Vector2d expected = params.T_grid_world.transform(bend_point(params.bend, turned));
  EXPECT_LT((warp.world_to_grid(p) - expected).norm(), 1e-12);
}

TEST(WarpFull, ReportsNonConvergence) {
  Random random(35);
  const SimulatedWarp warp(warehouse_warp(random));
  const Eigen::Vector2d in_room = warp.world_to_grid({63.5, 14.5});
  const InverseResult stopped = warp.grid_to_world(in_room, {1e-10, 0});
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(stopped.iterations, 0);
  EXPECT_GT(stopped.residual, 0.05);  // the start ignores the room's turn of ~0.15 m here
  const InverseResult solved = warp.grid_to_world(in_room);
  EXPECT_TRUE(solved.converged);
  EXPECT_GT(solved.iterations, 0);
  EXPECT_LT((solved.point - Eigen::Vector2d(63.5, 14.5)).norm(), 1e-9);
}

TEST(WarpFull, PoseHeadingFollowsTheLocalRotation) {
  Random random(36);
  const WarpParams params = warehouse_warp(random);
  const SimulatedWarp warp(params);
  // On the bend's axis, away from the room, a heading along the axis turns by k u.
  const double u = 80.0;
  const Pose2 on_axis{u, 25.0, 0.0};
  const Pose2 mapped = warp.pose_world_to_grid(on_axis);
  EXPECT_NEAR(normalize_angle(mapped.theta - params.T_grid_world.theta - params.bend.curvature * u),
              0.0, 1e-12);
  // Inside the rotated room a heading turns by the room's angle first, then through the bend's
  // R(k u) diag(1 - k v, 1) where the turned point lies (the axis is y = 25 along x here), then
  // by the rigid rotation.
  const Pose2 in_room{62.0, 12.0, 1.0};
  const RoomRotation& room = *params.room;
  const Eigen::Vector2d turned =
      room.center + rotation_2d(room.angle) * (in_room.translation() - room.center);
  const double k = params.bend.curvature;
  const Eigen::Vector2d heading = rotation_2d(params.T_grid_world.theta + k * turned.x()) *
                                  Eigen::Vector2d(1.0 - k * (turned.y() - 25.0), 1.0).asDiagonal() *
                                  rotation_2d(room.angle + in_room.theta) *
                                  Eigen::Vector2d::UnitX();
  const double expected = std::atan2(heading.y(), heading.x());
  EXPECT_NEAR(normalize_angle(warp.pose_world_to_grid(in_room).theta - expected), 0.0, 1e-12);
}

TEST(WarpFull, PoseRoundTrip) {
  Random random(37);
  const SimulatedWarp warp(warehouse_warp(random));
  for (int i = 0; i < 2000; ++i) {
    const bool near_room = i % 2 == 0;
    const Pose2 pose_in_world{near_room ? random.uniform(59, 65) : random.uniform(0, 100),
                              near_room ? random.uniform(9, 16) : random.uniform(0, 50),
                              random.uniform(-std::numbers::pi, std::numbers::pi)};
    const PoseInverseResult back = warp.pose_grid_to_world(warp.pose_world_to_grid(pose_in_world));
    EXPECT_TRUE(back.converged);
    EXPECT_LT((back.pose.translation() - pose_in_world.translation()).norm(), 1e-9);
    EXPECT_NEAR(normalize_angle(back.pose.theta - pose_in_world.theta), 0.0, 1e-9);
  }
}

TEST(WarpFull, RejectsNonFiniteParameters) {
  Random random(38);
  WarpParams params = warehouse_warp(random);
  params.bend.curvature = std::numeric_limits<double>::infinity();
  test::expect_input_error([&] { SimulatedWarp{params}; }, {"bend.curvature"});
  params = warehouse_warp(random);
  params.T_grid_world.theta = std::nan("");
  test::expect_input_error([&] { SimulatedWarp{params}; }, {"warp.T_grid_world"});
  params = warehouse_warp(random);
  params.room->band = -1;
  test::expect_input_error([&] { SimulatedWarp{params}; }, {"room.band"});
}

}  // namespace
}  // namespace floorgrid
