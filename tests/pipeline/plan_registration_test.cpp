#include "floorgrid/pipeline/plan_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/localization/likelihood_field_model.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

TEST(PlanRegistration, PlanPoseScalesTheMotionFromTheOrigin) {
  // The map pose 4 m ahead of the origin, turned by 0.5 rad, at 2 world metres per plan metre:
  // 2 plan metres ahead of the plan origin, turned by the same angle.
  const Pose2 origin_in_map{1.0, 2.0, 0.3};
  const Pose2 origin_in_plan{5.0, 6.0, -0.2};
  const PlanRegistration registration(origin_in_map, origin_in_plan, 2.0);
  const Pose2 ahead = origin_in_map.compose({4.0, 0.0, 0.5});
  const Pose2 p = registration.plan_pose(ahead);
  EXPECT_NEAR(p.x, 5.0 + 2.0 * std::cos(-0.2), 1e-12);
  EXPECT_NEAR(p.y, 6.0 + 2.0 * std::sin(-0.2), 1e-12);
  EXPECT_NEAR(p.theta, 0.3, 1e-12);
  const Pose2 same = registration.plan_pose(origin_in_map);
  EXPECT_NEAR(same.x, 5.0, 1e-12);
  EXPECT_NEAR(same.theta, -0.2, 1e-12);
  // map_pose undoes plan_pose.
  const Pose2 back = registration.map_pose(p);
  EXPECT_NEAR(back.x, ahead.x, 1e-12);
  EXPECT_NEAR(back.y, ahead.y, 1e-12);
  EXPECT_NEAR(normalize_angle(back.theta - ahead.theta), 0.0, 1e-12);
}

TEST(LocalRegistration, RecoversAKnownRigidOffsetAtThePlansScale) {
  const double scale = 1.25;           // world metres per plan metre
  const Pose2 offset{3.0, -1.0, 0.4};  // plan pose of the map origin, in plan metres
  LocalRegistration local(10, scale);
  for (std::size_t k = 0; k < 15; ++k) {
    const Pose2 in_map{0.5 * static_cast<double>(k), 0.1 * static_cast<double>(k * k) / 10.0,
                       0.05 * static_cast<double>(k)};
    const Eigen::Vector2d plan_xy = offset.transform(in_map.translation() / scale);
    local.add(k, in_map, {plan_xy.x(), plan_xy.y(), in_map.theta + offset.theta});
  }
  const Pose2 query{2.0, 3.0, -1.0};
  const Pose2 p = local.plan_pose(query);
  const Eigen::Vector2d expected = offset.transform(query.translation() / scale);
  EXPECT_NEAR(p.x, expected.x(), 1e-9);
  EXPECT_NEAR(p.y, expected.y(), 1e-9);
  EXPECT_NEAR(p.theta, normalize_angle(-1.0 + 0.4), 1e-9);
  // map_pose undoes plan_pose.
  const Pose2 back = local.map_pose(p);
  EXPECT_NEAR(back.x, query.x, 1e-9);
  EXPECT_NEAR(back.y, query.y, 1e-9);
  EXPECT_NEAR(normalize_angle(back.theta - query.theta), 0.0, 1e-9);
}

TEST(LocalRegistration, IsFreshOnlyWithEnoughRecentPairs) {
  LocalRegistration local(5, 1.0);
  EXPECT_FALSE(local.fresh(0, 1, 10));
  for (std::size_t k = 0; k < 3; ++k)
    local.add(k, {double(k), 0.0, 0.0}, {double(k), 0.0, 0.0});
  EXPECT_TRUE(local.fresh(2, 3, 10));
  EXPECT_FALSE(local.fresh(2, 4, 10));  // too few pairs
  EXPECT_TRUE(local.fresh(12, 3, 10));
  EXPECT_FALSE(local.fresh(13, 3, 10));  // the newest is too old
  local.clear();
  EXPECT_FALSE(local.fresh(2, 1, 10));
}

TEST(BuildSubmap, PutsTheEndpointsWhereTheWallsAre) {
  const VectorFloorplan room = test::asymmetric_room();
  const std::vector<Pose2> poses{{2.0, 4.0, 0.0}, {6.0, 2.0, 1.5}, {9.0, 4.0, 3.0}};
  const RobotLog log = test::log_along(room, poses);
  const std::vector<std::size_t> scans{0, 1, 2};
  const Pose2 origin = poses[0];
  SubmapOptions options;
  options.bin = 0.1;
  const ScanObservation submap = build_submap(log, scans, poses, origin, options);
  ASSERT_GT(submap.size(), 300u);
  // Every point, taken back into the world, lies on a wall (range noise 1 cm).
  double worst = 0.0;
  for (std::size_t i = 0; i < submap.size(); ++i) {
    const Eigen::Vector2d p = origin.transform(Eigen::Vector2d(submap.end_x[i], submap.end_y[i]));
    double nearest = 1e9;
    for (const Segment& s : room.segments())
      nearest = std::min(nearest, distance_to_segment(p, s));
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, 0.06);
  // A pose per scan.
  test::expect_input_error(
      [&] {
        build_submap(log, scans, {poses.data(), 2}, origin, options);
      },
      {"submap.poses"});
}

TEST(RegisterOnPlan, FindsThePoseAndScaleOfARunOnAPlanDrawnAtAnotherScale) {
  // The plan is the world drawn at 1 / 1.1, shifted and turned: T_plan_world.
  const double scale = 1.1;  // world metres per plan metre
  const Pose2 T_plan_world{2.0, 1.0, 0.3};
  const VectorFloorplan world = test::asymmetric_room();
  VectorFloorplan plan;
  for (const Segment& s : world.segments())
    plan.add_segment(T_plan_world.transform(s.a / scale), T_plan_world.transform(s.b / scale),
                     "WALLS");
  const OccupancyGrid plan_grid = test::room_grid(plan);
  const std::vector<Pose2> poses{
      {2.0, 4.0, 0.0}, {6.0, 2.0, 1.5}, {9.0, 4.0, 3.0}, {8.0, 7.2, -1.0}};
  const RobotLog log = test::log_along(world, poses);
  const std::vector<std::size_t> scans{0, 1, 2, 3};
  const ScanObservation submap = build_submap(log, scans, poses, poses[0]);
  const LikelihoodFieldModel model(plan_grid, LikelihoodFieldOptions{.sigma_hit = 0.15});
  PlanRegistrationOptions options;
  options.seeding.headings = 36;
  options.seeding.scales = 5;
  options.coarse_points = 400;
  const PlanRegistrationResult found = register_on_plan(
      plan_grid, model, submap, poses[0], ScaleRange{.min = 0.9, .max = 1.3}, 1.0, options);
  // The truth: the first pose's plan pose.
  const Eigen::Vector2d truth_xy = T_plan_world.transform(poses[0].translation() / scale);
  const Pose2 p = found.registration.origin_in_plan();
  EXPECT_LT(std::hypot(p.x - truth_xy.x(), p.y - truth_xy.y()), 0.2);
  EXPECT_LT(std::abs(normalize_angle(p.theta - (poses[0].theta + T_plan_world.theta))), 0.1);
  EXPECT_NEAR(found.registration.scale(), scale, 0.03);
  EXPECT_GT(found.log_likelihood, found.runner_up_log_likelihood);
  // Another pose of the run maps through the registration onto its plan pose.
  const Pose2 other = found.registration.plan_pose(poses[2]);
  const Eigen::Vector2d other_truth = T_plan_world.transform(poses[2].translation() / scale);
  EXPECT_LT(std::hypot(other.x - other_truth.x(), other.y - other_truth.y()), 0.3);
}

TEST(RegisterOnPlan, RefusesAnEmptyRun) {
  const OccupancyGrid plan_grid = test::room_grid(test::asymmetric_room());
  const LikelihoodFieldModel model(plan_grid);
  test::expect_input_error(
      [&] {
        register_on_plan(plan_grid, model, ScanObservation{}, Pose2(), std::nullopt, 1.0, {});
      },
      {"no laser endpoints"});
}

}  // namespace
}  // namespace floorgrid
