// The plan poses' pull along the robot's heading, measured from revisits: a robot driving a
// loop of corridors both ways round, its plan poses ahead of its gridmap poses by a known pull,
// through a known similarity.
#include "floorgrid/pipeline/pose_pull.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

constexpr double kPlanScale = 1.25;           // world metres per plan metre
constexpr double kPlanTurn = 0.4;             // radians from the gridmap's axes to the plan's
constexpr double kScanPeriod = 0.2;           // seconds between scans
constexpr double kStep = 0.1;                 // metres the robot drives between scans
const Eigen::Vector2d kPlanShift{3.0, -2.0};  // plan metres

/// The plan pose of a gridmap pose through the similarity, `pull` world metres ahead along
/// the heading, with `noise` world metres of independent noise per axis.
Pose2 plan_pose_of(const Pose2& grid, double pull, double noise, Random& random) {
  const double theta = grid.theta + kPlanTurn;
  const Eigen::Vector2d ahead(std::cos(theta), std::sin(theta));
  const Eigen::Vector2d world =
      grid.translation() + Eigen::Vector2d(random.normal(noise), random.normal(noise));
  const Eigen::Vector2d plan =
      rotation_2d(kPlanTurn) * world / kPlanScale + kPlanShift + pull / kPlanScale * ahead;
  return {plan.x(), plan.y(), theta};
}

/// A 20 x 10 m loop of corridors driven `laps` times, anticlockwise and then, when
/// `both_ways`, as often clockwise: samples every kStep metres.
std::vector<PullSample> loop_run(double pull, double noise, int laps, bool both_ways,
                                 std::uint64_t seed = 1) {
  const std::vector<Eigen::Vector2d> anticlockwise{{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  const std::vector<Eigen::Vector2d> clockwise(anticlockwise.rbegin(), anticlockwise.rend());
  Random random(seed);
  std::vector<PullSample> samples;
  double time = 0.0;
  const auto drive = [&](const std::vector<Eigen::Vector2d>& corners) {
    for (std::size_t c = 0; c < corners.size(); ++c) {
      const Eigen::Vector2d from = corners[c], leg = corners[(c + 1) % corners.size()] - from;
      const double heading = std::atan2(leg.y(), leg.x());
      for (double s = 0.0; s < leg.norm(); s += kStep) {
        const Eigen::Vector2d p = from + s / leg.norm() * leg;
        const Pose2 grid{p.x(), p.y(), heading};
        samples.push_back({time, plan_pose_of(grid, pull, noise, random), grid});
        time += kScanPeriod;
      }
    }
  };
  for (int lap = 0; lap < laps; ++lap)
    drive(anticlockwise);
  for (int lap = 0; both_ways && lap < laps; ++lap)
    drive(clockwise);
  return samples;
}

TEST(PosePull, MeasuresAKnownPullThroughASimilarity) {
  for (const double pull : {0.08, -0.03}) {
    const auto measured = measure_pose_pull(loop_run(pull, 0.01, 2, true), kPlanScale, {});
    ASSERT_TRUE(measured);
    EXPECT_NEAR(measured->along_m, pull, 0.005) << pull;
    EXPECT_LT(measured->std_m, 0.005);
    EXPECT_GT(measured->scans, 500u);
    EXPECT_TRUE(measured->applied);
  }
}

TEST(PosePull, FindsNoneWhereThereIsNone) {
  const auto measured = measure_pose_pull(loop_run(0.0, 0.02, 2, true, 2), kPlanScale, {});
  ASSERT_TRUE(measured);
  EXPECT_NEAR(measured->along_m, 0.0, 0.005);
}

TEST(PosePull, NeedsRevisitsFacingAnotherWay) {
  // Driven the same way round every time: the loop's corners are the only places seen facing
  // another way, and only by the next scans of the same pass (within min_time_apart) or by
  // the next laps' (a quarter turn apart).
  PosePullOptions half_turns;
  half_turns.min_turn = 2.5;  // radians: only a drive back the other way counts
  EXPECT_FALSE(measure_pose_pull(loop_run(0.08, 0.01, 3, false), kPlanScale, half_turns));
  EXPECT_FALSE(measure_pose_pull({}, kPlanScale, {}));
}

TEST(PosePull, IsNotTakenOutWhenUncertainLargeOrSwitchedOff) {
  const std::vector<PullSample> run = loop_run(0.08, 0.01, 1, true);
  PosePullOptions options;
  options.min_scans = 100000;
  EXPECT_FALSE(measure_pose_pull(run, kPlanScale, options)->applied);
  options = {};
  options.max_pull = 0.05;
  EXPECT_FALSE(measure_pose_pull(run, kPlanScale, options)->applied);
  options = {};
  options.max_std = 0.0;
  EXPECT_FALSE(measure_pose_pull(run, kPlanScale, options)->applied);
  options = {};
  options.enabled = false;
  EXPECT_FALSE(measure_pose_pull(run, kPlanScale, options)->applied);
  // Noise of two metres per scan: the standard error is far above max_std.
  const auto noisy = measure_pose_pull(loop_run(0.08, 2.0, 1, true, 3), kPlanScale, {});
  ASSERT_TRUE(noisy);
  EXPECT_GT(noisy->std_m, PosePullOptions{}.max_std);
  EXPECT_FALSE(noisy->applied);
}

TEST(PosePull, TakingItOutMovesThePoseBackAlongItsHeading) {
  const Pose2 pose{1.0, 2.0, std::numbers::pi / 2};
  const Pose2 back = without_pull(pose, 0.25, 0.5);  // 0.25 world m = 0.5 plan m
  EXPECT_NEAR(back.x, 1.0, 1e-12);
  EXPECT_NEAR(back.y, 1.5, 1e-12);
  EXPECT_EQ(back.theta, pose.theta);
  Random random(4);
  const Pose2 grid{5.0, 0.0, 0.0};
  const Pose2 pulled = plan_pose_of(grid, 0.08, 0.0, random);
  const Pose2 exact = plan_pose_of(grid, 0.0, 0.0, random);
  const Pose2 mended = without_pull(pulled, 0.08, kPlanScale);
  EXPECT_NEAR(mended.x, exact.x, 1e-12);
  EXPECT_NEAR(mended.y, exact.y, 1e-12);
}

}  // namespace
}  // namespace floorgrid
