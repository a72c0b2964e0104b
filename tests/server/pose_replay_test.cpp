// The replay of a run as the live pose: each pose after its time since the last (garbage gaps
// replaced), posted in order, and a stop that does not wait for the next pose.
#include "floorgrid/server/pose_replay.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "tests/support/test_data.hpp"

namespace floorgrid::server {
namespace {

std::shared_ptr<const PointMapping> identity_model() {
  return test::fitted(
      "gt", test::pairs_of({{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
}

std::vector<io::TimedPose> track_of(const std::vector<double>& times) {
  std::vector<io::TimedPose> track;
  for (std::size_t i = 0; i < times.size(); ++i)
    track.push_back({times[i], Pose2{1.0 * i, -0.5 * i, 0.1 * i}});
  return track;
}

TEST(PoseReplay, WaitsAreTheTimesBetweenScansWithGarbageGapsReplaced) {
  ReplayOptions options;
  options.max_gap_s = 2.0;
  options.gap_s = 0.1;
  const std::vector<double> waits =
      replay_waits(track_of({10.0, 10.25, 10.25, 9.0, 15.0, std::nan(""), 16.0, 16.5}), options);
  const std::vector<double> expected = {0.0, 0.25, 0.1, 0.1, 0.1, 0.1, 0.1, 0.5};
  ASSERT_EQ(waits.size(), expected.size());
  for (std::size_t i = 0; i < waits.size(); ++i)
    EXPECT_NEAR(waits[i], expected[i], 1e-12) << i;
}

TEST(PoseReplay, EveryPoseIsPostedInOrderAndTheLastStays) {
  ViewerSession session(identity_model(), "replay");
  ReplayOptions options;
  options.speed = 100.0;  // 5 poses 0.2 s apart: 10 ms in all
  options.loop = false;
  PoseReplay replay(session, track_of({0.0, 0.2, 0.4, 0.6, 0.8}), options);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (replay.posted() < 5 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_EQ(replay.posted(), 5u);
  const RobotPose last = session.robot_pose();
  EXPECT_EQ(last.sequence, 5u);
  EXPECT_DOUBLE_EQ(last.pose_in_grid.x, 4.0);
  EXPECT_DOUBLE_EQ(last.pose_in_grid.y, -2.0);
  EXPECT_DOUBLE_EQ(last.pose_in_grid.theta, 0.4);
}

TEST(PoseReplay, StopReturnsAtOnceMidWait) {
  ViewerSession session(identity_model(), "replay");
  ReplayOptions options;
  options.max_gap_s = 1000.0;
  PoseReplay replay(session, track_of({0.0, 600.0}), options);  // the second pose in 10 minutes
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (replay.posted() < 1 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const auto start = std::chrono::steady_clock::now();
  replay.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(replay.posted(), 1u);
  EXPECT_EQ(session.robot_pose().sequence, 1u);
}

}  // namespace
}  // namespace floorgrid::server
