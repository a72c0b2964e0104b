#include "floorgrid/pipeline/filter_runner.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/localization/likelihood_field_model.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

struct Room {
  VectorFloorplan walls = test::asymmetric_room();
  OccupancyGrid grid = test::room_grid(walls);
  WallField field{walls, grid.geometry()};  // the exact walls, not their cells
  LikelihoodFieldModel model{grid};
};

const Room& room() {
  static const Room r;
  return r;
}

TrackingStart around(const Pose2& pose, double sigma, double heading_sigma) {
  return TrackingStart{.pose = pose, .position_sigma = sigma, .heading_sigma = heading_sigma};
}

/// How the tests' runners prepare each scan.
constexpr ObservationOptions kSixtyBeams{.max_beams = 60};

TEST(ApplyProposal, MovesTheCloudOntoTheMatchedPose) {
  const Pose2 truth{3.0, 5.0, 0.2};
  const RobotLog log = test::log_along(room().walls, {truth});
  ParticleFilter filter(ParticleFilterOptions{}, 3);
  // A tight cloud 0.2 m and 0.05 rad off the truth.
  filter.initialize_tracking(around(truth.compose({0.15, -0.13, 0.05}), 0.01, 0.005));
  const ScanMatch m =
      apply_proposal(filter, room().field, make_observation(log.scans[0], {.max_beams = 180}), {});
  ASSERT_TRUE(m.ok());
  const PoseEstimate moved = estimate_pose(filter.particles());
  EXPECT_LT((moved.pose.translation() - truth.translation()).norm(), 0.03);
  EXPECT_LT(std::abs(normalize_angle(moved.pose.theta - truth.theta)), 0.01);
}

TEST(FilterRunner, UpdatesOnlyOnceTheRobotHasMovedEnough) {
  // Standing still for three scans, then 0.1 m steps.
  std::vector<Pose2> poses(4, Pose2{2.0, 4.0, 0.0});
  for (int k = 1; k <= 3; ++k)
    poses.push_back({2.0 + 0.1 * k, 4.0, 0.0});
  const RobotLog log = test::log_along(room().walls, poses);
  ParticleFilter filter(ParticleFilterOptions{}, 1);
  filter.initialize_tracking(around(poses[0], 0.05, 0.02));
  FilterRunner runner(std::move(filter), room().model, room().field, log, kSixtyBeams, {});
  std::vector<bool> updated;
  for (std::size_t i = 0; i < log.scans.size(); ++i)
    updated.push_back(runner.step(i).updated);
  // The first scan updates; standing still does not (update_min_translation 0.05 m); each
  // 0.1 m step does.
  EXPECT_EQ(updated, (std::vector<bool>{true, false, false, false, true, true, true}));
}

TEST(FilterRunner, TracksARunAndRefinesEachPoseOntoTheWalls) {
  std::vector<Pose2> poses;
  for (int k = 0; k < 60; ++k)
    poses.push_back({2.0 + 0.12 * k, 5.0 + 0.5 * std::sin(0.1 * k), 0.05 * std::cos(0.1 * k)});
  const RobotLog log = test::log_along(room().walls, poses);
  ParticleFilter filter(ParticleFilterOptions{}, 1);
  filter.initialize_tracking(around(poses[0].compose({0.1, 0.1, 0.03}), 0.1, 0.05));
  FilterRunner runner(std::move(filter), room().model, room().field, log, kSixtyBeams, {});
  std::size_t converged = 0, matched = 0;
  double worst_match = 0.0, sum_match = 0.0;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const FilterRecord r = runner.step(i);
    converged += r.converged;
    if (r.matched && r.match.ok()) {
      ++matched;
      const double error = (r.match.pose.translation() - poses[i].translation()).norm();
      worst_match = std::max(worst_match, error);
      sum_match += error;
    }
  }
  EXPECT_GE(converged, 40u);
  EXPECT_GE(matched, 40u);
  // The refined poses are far better than the filter's spread (0.1 m): on the exact walls,
  // within 2 cm of the truth, 1 cm on average (range noise 1 cm).
  EXPECT_LT(worst_match, 0.02);
  EXPECT_LT(sum_match / static_cast<double>(matched), 0.01);
  EXPECT_GT(runner.evaluations(), 0u);
}

TEST(FilterRunner, PreparesEachScanWithItsObservationOptions) {
  // The runner prepares each scan as it steps, with the options it was given: the same seed
  // with a third of the beams weighs a third of the evaluations and follows another course.
  std::vector<Pose2> poses;
  for (int k = 0; k < 40; ++k)
    poses.push_back({2.0 + 0.15 * k, 5.0 + 0.4 * std::sin(0.15 * k), 0.05 * std::cos(0.1 * k)});
  const RobotLog log = test::log_along(room().walls, poses);
  const auto runner_of = [&](const ObservationOptions& observation) {
    ParticleFilter filter(ParticleFilterOptions{}, 7);
    filter.initialize_tracking(around(poses[0].compose({0.1, -0.1, 0.02}), 0.1, 0.05));
    return FilterRunner(std::move(filter), room().model, room().field, log, observation, {});
  };
  FilterRunner sixty = runner_of(kSixtyBeams);
  FilterRunner twenty = runner_of(ObservationOptions{.max_beams = 20});
  std::size_t different = 0;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const FilterRecord a = sixty.step(i), b = twenty.step(i);
    different += a.pose.x != b.pose.x || a.fit != b.fit;
  }
  EXPECT_EQ(sixty.evaluations(), 3 * twenty.evaluations());
  EXPECT_GT(different, 0u);
}

/// A run of 1 m steps across the room, and its log with odometry that turns 4 degrees too far
/// on every step (the log's poses drift; the scans are taken at the true poses).
struct DriftingRun {
  std::vector<Pose2> truth;
  RobotLog log;
};

DriftingRun drifting_run() {
  DriftingRun run;
  for (int k = 0; k < 10; ++k)
    run.truth.push_back({1.5 + 0.9 * k, 2.0 + 0.4 * k, 0.42});
  run.log = test::log_along(room().walls, run.truth);
  Pose2 odometry = run.truth[0];
  for (std::size_t i = 1; i < run.truth.size(); ++i) {
    const Pose2 step = run.truth[i - 1].between(run.truth[i]);
    odometry = odometry.compose(Pose2{step.x, step.y, step.theta + 0.07});
    run.log.scans[i].robot_pose = run.log.scans[i].laser_pose = odometry;
  }
  return run;
}

TEST(FilterRunner, AGuidedFilterMovesByTheGuideNotTheDriftingOdometry) {
  const DriftingRun run = drifting_run();
  // Scans of a blank map: the filter learns nothing from them, only the motion moves it.
  const LikelihoodFieldModel blank{OccupancyGrid(room().grid.geometry())};
  double guided_error = 0.0, odometry_error = 0.0;
  for (const bool guided : {true, false}) {
    ParticleFilter filter(ParticleFilterOptions{}, 1);
    filter.initialize_tracking(around(run.truth[0], 0.02, 0.01));
    FilterRunnerOptions options;
    options.improved_proposal = options.refine = false;
    FilterRunner runner(std::move(filter), blank, room().field, run.log, kSixtyBeams, options);
    if (guided)
      runner.guide({run.truth.begin(), run.truth.end()});
    FilterRecord last;
    for (std::size_t i = 0; i < run.log.scans.size(); ++i)
      last = runner.step(i);
    const double error = (last.pose.translation() - run.truth.back().translation()).norm();
    (guided ? guided_error : odometry_error) = error;
    EXPECT_EQ(runner.guided_steps(), guided ? run.log.scans.size() - 1 : 0u);
  }
  // 4 degrees a step over 9 steps of a metre: the odometry ends metres off, the guide within
  // its noise (4.5 cm per metre).
  EXPECT_GT(odometry_error, 1.5);
  EXPECT_LT(guided_error, 0.3);
}

TEST(FilterRunner, AGuideThatJumpsAwayFromTheOdometryIsNotFollowed) {
  const DriftingRun run = drifting_run();
  std::vector<std::optional<Pose2>> guide(run.truth.begin(), run.truth.end());
  guide[4] = guide[4]->compose({2.0, 0.0, 0.0});  // 2 m off: both steps through it are refused
  guide[7].reset();                               // unknown: both steps through it too
  ParticleFilter filter(ParticleFilterOptions{}, 1);
  filter.initialize_tracking(around(run.truth[0], 0.02, 0.01));
  FilterRunner runner(std::move(filter), room().model, room().field, run.log, kSixtyBeams, {});
  runner.guide(guide);
  for (std::size_t i = 0; i < run.log.scans.size(); ++i)
    runner.step(i);
  EXPECT_EQ(runner.guided_steps(), run.log.scans.size() - 1 - 4);
}

}  // namespace
}  // namespace floorgrid
