// The robot's tour: driven once, and driven over and over for a given duration.
#include "floorgrid/simulation/robot_tour.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace floorgrid {
namespace {

const std::vector<Eigen::Vector2d> kLShape = {{0.0, 0.0}, {10.0, 0.0}, {10.0, 5.0}};

TEST(RobotTour, DrivenForADurationLastsThatLongAndNeverJumps) {
  TourOptions options;
  options.tick = 1.0 / 15.0;
  const std::vector<TimedPose> once = drive_tour(kLShape, options);
  const double once_seconds = once.back().time - once.front().time;
  ASSERT_GT(once_seconds, 20.0);
  const double duration = 3.5 * once_seconds;
  const std::vector<TimedPose> poses = drive_tour_for(kLShape, duration, options);
  ASSERT_GT(poses.size(), 2u);
  EXPECT_EQ(poses.front().time, options.start_time);
  EXPECT_NEAR(poses.back().time - poses.front().time, duration, 0.5 * options.tick + 1e-9);
  EXPECT_NEAR(static_cast<double>(poses.size() - 1), duration / options.tick, 1.0);
  // One pose a tick, each within a tick's driving of the last (no jump back to the start).
  for (std::size_t i = 1; i < poses.size(); ++i) {
    ASSERT_NEAR(poses[i].time - poses[i - 1].time, options.tick, 1e-9) << i;
    ASSERT_LE((poses[i].pose.translation() - poses[i - 1].pose.translation()).norm(),
              options.speed * options.tick + 1e-9)
        << i;
  }
  // Forth, back, forth, back: at either end of the tour more than once.
  int at_end = 0, at_start = 0;
  bool near_end = false, near_start = true;
  for (const TimedPose& p : poses) {
    const bool end_now = (p.pose.translation() - kLShape.back()).norm() < 0.2;
    const bool start_now = (p.pose.translation() - kLShape.front()).norm() < 0.2;
    at_end += end_now && !near_end;
    at_start += start_now && !near_start;
    near_end = end_now;
    near_start = start_now;
  }
  EXPECT_EQ(at_end, 2);
  EXPECT_EQ(at_start, 1);
  // The first pass is the tour driven once, pose for pose.
  for (std::size_t i = 0; i + 1 < once.size(); ++i) {
    ASSERT_EQ(poses[i].pose.x, once[i].pose.x) << i;
    ASSERT_EQ(poses[i].pose.y, once[i].pose.y) << i;
  }
}

TEST(RobotTour, ShortDurationCutsTheTourShort) {
  const std::vector<TimedPose> poses = drive_tour_for(kLShape, 5.0);
  EXPECT_NEAR(poses.back().time - poses.front().time, 5.0, 0.05 + 1e-9);
  EXPECT_LT(poses.back().pose.x, 5.0);
}

TEST(RobotTour, NoDurationOrNoTourDrivesTheTourOnce) {
  const std::vector<TimedPose> once = drive_tour(kLShape);
  EXPECT_EQ(drive_tour_for(kLShape, 0.0).size(), once.size());
  EXPECT_EQ(drive_tour_for(kLShape, std::nan("")).size(), once.size());
  EXPECT_EQ(drive_tour_for({{1.0, 1.0}}, 100.0).size(), 1u);
  EXPECT_TRUE(drive_tour_for({}, 100.0).empty());
}

}  // namespace
}  // namespace floorgrid
