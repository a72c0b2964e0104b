#include "floorgrid/pipeline/submap_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/localization/likelihood_field_model.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

/// The room drawn at 1 / 1.1, shifted and turned; a run of scans through the world room, with
/// the gridmap filter's poses exact.
struct RoomRun {
  static constexpr double scale = 1.1;  // world metres per plan metre
  const Pose2 T_plan_world{2.0, 1.0, 0.3};
  const VectorFloorplan world = test::asymmetric_room();
  VectorFloorplan plan;
  OccupancyGrid plan_grid;
  std::vector<Pose2> poses;
  RobotLog log;
  std::unique_ptr<LikelihoodFieldModel> field;  // the plan's, as the plan filter's

  RoomRun() {
    for (const Segment& s : world.segments())
      plan.add_segment(T_plan_world.transform(s.a / scale), T_plan_world.transform(s.b / scale),
                       "WALLS");
    plan_grid = test::room_grid(plan);
    // Along the room, 0.4 m apart, turning slowly; back; and along again.
    for (int k = 0; k < 48; ++k) {
      const int j = k < 16 ? k : k < 32 ? 31 - k : k - 32;
      poses.push_back({1.5 + 0.4 * j, 4.0 + 0.1 * j, 0.1 * j + (k >= 16 && k < 32 ? 3.0 : 0.0)});
    }
    log = test::log_along(world, poses);
    field = std::make_unique<LikelihoodFieldModel>(plan_grid,
                                                   LikelihoodFieldOptions{.sigma_hit = 0.15});
  }
  /// The true plan pose of world pose `p`.
  Pose2 plan_pose(const Pose2& p) const {
    const Eigen::Vector2d xy = T_plan_world.transform(p.translation() / scale);
    return {xy.x(), xy.y(), p.theta + T_plan_world.theta};
  }
};

/// The check's options, enabled.
SubmapCheckOptions enabled() {
  SubmapCheckOptions options;
  options.enabled = true;
  return options;
}

/// A check on `run` that was given every scan of its run.
SubmapCheck given_every_scan(const SubmapCheckOptions& options, const RoomRun& run) {
  SubmapCheck check(options, run.log, *run.field, RoomRun::scale);
  for (std::size_t i = 0; i < run.poses.size(); ++i)
    check.add(i, run.poses[i]);
  return check;
}

TEST(SubmapCheck, RePlacesAPlanFilterThatSettledMetresOffWhereTheRunsSubmapFits) {
  const RoomRun run;
  SubmapCheckOptions options = enabled();
  options.confirmations = 2;
  SubmapCheck check(options, run.log, *run.field, RoomRun::scale);
  // The plan filter 1.6 world metres off along the plan's x and 0.05 rad turned; the global
  // registration a metre off the truth too, the other way.
  const auto off = [&](std::size_t i) {
    const Pose2 truth = run.plan_pose(run.poses[i]);
    return Pose2{truth.x + 1.6 / RoomRun::scale, truth.y, truth.theta + 0.05};
  };
  const auto registered = [&](std::size_t i) {
    const Pose2 truth = run.plan_pose(run.poses[i]);
    return Pose2{truth.x - 1.0 / RoomRun::scale, truth.y, truth.theta};
  };
  for (std::size_t i = 0; i < 16; ++i)
    check.add(i, run.poses[i]);
  ASSERT_TRUE(check.due(15));
  // The first check finds it; the plan filter is re-placed when the next one finds it again.
  EXPECT_FALSE(check.check(15, run.poses[15], off(15), registered(15)).has_value());
  EXPECT_FALSE(check.due(15 + options.every));  // no scan joined since
  const std::size_t last = 15 + options.every;
  for (std::size_t i = 16; i <= last; ++i)
    check.add(i, run.poses[i]);
  ASSERT_TRUE(check.due(last));
  const std::optional<SubmapRelocation> moved =
      check.check(last, run.poses[last], off(last), registered(last));
  ASSERT_TRUE(moved.has_value());
  const Pose2 truth = run.plan_pose(run.poses[last]);
  EXPECT_LT(std::hypot(moved->plan_pose.x - truth.x, moved->plan_pose.y - truth.y) * RoomRun::scale,
            0.1);
  EXPECT_LT(std::abs(normalize_angle(moved->plan_pose.theta - truth.theta)), 0.02);
  EXPECT_NEAR(moved->shift, 1.6, 0.15);
  EXPECT_GT(moved->share_after, 0.9);  // range noise 1 cm against a 0.15 m likelihood
  EXPECT_GE(moved->share_after, moved->share_before + options.min_gain);
  // Checked again at once: not due (no scan joined since).
  EXPECT_FALSE(check.due(last));
  // With one confirmation (the default), the first check re-places it.
  const SubmapCheckOptions once = enabled();
  SubmapCheck first(once, run.log, *run.field, RoomRun::scale);
  for (std::size_t i = 0; i < 16; ++i)
    first.add(i, run.poses[i]);
  EXPECT_TRUE(first.check(15, run.poses[15], off(15), registered(15)).has_value());
  // Where the global registration puts the robot more than max_from_registration (2 m) from
  // the truth, the check does not take the truth: a drawing's door pitch would fit as well.
  // (One confirmation, so that every check could re-place it.)
  SubmapCheck far(once, run.log, *run.field, RoomRun::scale);
  int checks = 0;
  for (std::size_t i = 0; i < run.poses.size(); ++i) {
    far.add(i, run.poses[i]);
    if (far.due(i)) {
      const Pose2 astray{off(i).x + 0.9 / RoomRun::scale, off(i).y, off(i).theta};
      EXPECT_FALSE(far.check(i, run.poses[i], off(i), astray).has_value()) << "scan " << i;
      ++checks;
    }
  }
  EXPECT_GE(checks, 2);
}

TEST(SubmapCheck, LeavesAPlanFilterWhereTheSubmapFitsAndOneOffByLessThanMinShift) {
  const RoomRun run;
  const SubmapCheckOptions options = enabled();
  SubmapCheck check = given_every_scan(options, run);
  const std::size_t last = run.poses.size() - 1;
  const Pose2 truth = run.plan_pose(run.poses[last]);
  EXPECT_FALSE(check.check(last, run.poses[last], truth, truth).has_value());
  // 0.3 m off: within min_shift, the filter's own business (its scan matcher).
  SubmapCheck again = given_every_scan(options, run);
  EXPECT_FALSE(again
                   .check(last, run.poses[last],
                          {truth.x, truth.y + 0.3 / RoomRun::scale, truth.theta}, truth)
                   .has_value());
}

TEST(SubmapCheck, ChecksOnlyWithEnoughScansSpacedByTheRobotsMotionAndWhenEnabled) {
  const RoomRun run;
  SubmapCheckOptions options = enabled();
  SubmapCheck check(options, run.log, *run.field, RoomRun::scale);
  // The robot standing still: one scan joins, however many are added.
  for (std::size_t i = 0; i < 30; ++i)
    check.add(i, run.poses[0]);
  EXPECT_FALSE(check.due(30));  // 1 of min_scans 10
  for (std::size_t i = 0; i < run.poses.size(); ++i)
    check.add(31 + i, run.poses[i]);
  EXPECT_TRUE(check.due(50));
  options.enabled = false;
  EXPECT_FALSE(check.due(50));
}

}  // namespace
}  // namespace floorgrid
