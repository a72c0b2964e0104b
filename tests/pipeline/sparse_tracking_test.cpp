// The dual localization on a sparse log (issue 10, "sparse and fast logs"): the simulated office
// thinned to a scan every metre or 20 degrees, as the Radish logs are, with odometry noise at
// the SPEC's levels on those large steps. Both filters must stay converged and right.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/pipeline/plan_tracking.hpp"
#include "floorgrid/robot/odometry_noise.hpp"
#include "floorgrid/simulation/simulator.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// The simulated office, its truth and a sparse noisy log of it.
struct SparseOffice {
  test::TempDir dir;
  SimulatedDataset sim = simulate("office", 1);
  io::LoadedDataset data;
  RobotLog log;              ///< every scan after >= 1 m or >= 20 degrees, noisy odometry
  std::vector<Pose2> truth;  ///< the true world pose of each of log's scans
  double median_step = 0.0;  ///< metres between the scans
  double median_turn = 0.0;  ///< radians
};

/// The true pose at time `t` (the tick nearest to it).
Pose2 true_pose_at(const std::vector<TimedPose>& trajectory, double t) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                                   [](const TimedPose& p, double time) { return p.time < time; });
  if (it == trajectory.end())
    return trajectory.back().pose;
  if (it != trajectory.begin() && t - std::prev(it)->time < it->time - t)
    return std::prev(it)->pose;
  return it->pose;
}

double median(std::vector<double> v) {
  if (v.empty())
    return std::numeric_limits<double>::infinity();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Fills `o` (its folder and simulation made): the dataset read back and the sparse log.
void make_sparse(SparseOffice& o) {
  io::write_simulated_dataset(o.sim, o.dir.path(), false);
  o.data = io::load_dataset(o.dir.path());
  // Keep a scan once the robot has truly moved a metre or turned 20 degrees since the last
  // one kept; its odometry is the true pose, then the SPEC's noise on each (large) step.
  RobotLog exact = *o.data.log;
  exact.scans.clear();
  std::vector<double> steps, turns;
  for (const LaserScan& scan : o.data.log->scans) {
    const Pose2 pose = true_pose_at(o.sim.true_trajectory, scan.timestamp);
    if (!o.truth.empty()) {
      const double step = (pose.translation() - o.truth.back().translation()).norm();
      const double turn = std::abs(normalize_angle(pose.theta - o.truth.back().theta));
      if (step < 1.0 && turn < 20.0 * M_PI / 180.0)
        continue;
      steps.push_back(step);
      turns.push_back(turn);
    }
    LaserScan kept = scan;
    kept.laser_pose = pose.compose(scan.robot_pose.between(scan.laser_pose));
    kept.robot_pose = pose;
    exact.scans.push_back(kept);
    o.truth.push_back(pose);
    if (exact.scans.size() == 300)
      break;
  }
  o.log = add_odometry_noise(exact, MotionNoise{}, 7);
  o.median_step = median(steps);
  o.median_turn = median(turns);
}

const SparseOffice& sparse_office() {
  static SparseOffice office;
  static const bool made = (make_sparse(office), true);
  (void)made;
  return office;
}

struct Errors {
  double plan = 0.0;  ///< median position error of the plan filter, world metres
  double grid = 0.0;  ///< of the gridmap filter
  double pairs = 0.0;
};

/// The filters' errors against the truth on the scans where both were converged.
Errors errors(const SparseOffice& o, const DualLocalization& r) {
  const double plan_scale = o.sim.plan_scale;  // plan metres per world metre
  std::vector<double> plan, grid, pairs;
  for (const ScanRecord& s : r.scans) {
    if (!(s.plan.converged && s.grid.converged))
      continue;
    const Eigen::Vector2d world = o.truth[s.scan].translation();
    plan.push_back((s.plan.pose.translation() / plan_scale - world).norm());
    grid.push_back(
        (s.grid.pose.translation() - o.data.truth_warp->plan_to_grid(world * plan_scale)).norm());
  }
  for (Eigen::Index i = 0; i < r.pairs.size(); ++i)
    pairs.push_back((o.data.truth_warp->plan_to_grid(r.pairs.points_in_plan.col(i)) -
                     r.pairs.points_in_grid.col(i))
                        .norm());
  return {median(plan), median(grid), median(pairs)};
}

DualLocalization localize(const SparseOffice& o, const DualLocalizerOptions& options) {
  return localize_dual(
      {.plan = o.data.plan_grid,
       .gridmap = o.data.gridmap,
       .log = o.log,
       .start = StartPoses{o.data.manifest.initial_pose->plan, o.data.manifest.initial_pose->grid},
       .plan_scale = o.data.manifest.floorplan_scale,
       .plan_geometry = &*o.data.plan},
      options);
}

TEST(SparseTracking, TheLogIsAsSparseAsTheRadishLogs) {
  const SparseOffice& o = sparse_office();
  ASSERT_GE(o.log.scans.size(), 200u);
  EXPECT_GE(o.median_step, 0.5);
  // The odometry drifts from the truth as on a real robot (SPEC noise on metre steps).
  EXPECT_GT((o.log.scans.back().robot_pose.translation() - o.truth.back().translation()).norm(),
            1.0);
}

TEST(SparseTracking, BothFiltersStayConvergedAndRightOnLargeSteps) {
  const SparseOffice& o = sparse_office();
  const DualLocalization r = localize(o, {});
  ASSERT_TRUE(r.status.ok) << r.status.message;
  // Moving the plan filter by the odometry instead (guide_plan_by_gridmap off, the plan
  // filter left to its own recovery) gave 0.85 converged, the plan 0.10 m off and the pairs
  // 0.090 m.
  EXPECT_GE(r.converged_fraction, 0.9);
  EXPECT_GT(r.plan_guided_steps, o.log.scans.size() / 2);
  const Errors e = errors(o, r);
  EXPECT_LE(e.plan, 0.09);
  EXPECT_LE(e.grid, 0.06);
  EXPECT_GT(r.pairs.size(), 3000);
  EXPECT_LE(e.pairs, 0.085);
}

TEST(SparseTracking, GridmapGuideFollowsOnlyTheConvergedGridmapFilter) {
  DualLocalization r;
  r.scans.resize(3);
  r.scans[0].grid.converged = true;
  r.scans[0].grid.pose = {1.0, 2.0, 0.5};
  r.scans[2].grid.pose = {5.0, 2.0, 0.5};  // not converged: no guide there
  const std::vector<std::optional<Pose2>> guide = gridmap_guide(r);
  ASSERT_EQ(guide.size(), 3u);
  ASSERT_TRUE(guide[0].has_value());
  EXPECT_DOUBLE_EQ(guide[0]->x, 1.0);
  EXPECT_FALSE(guide[1].has_value());
  EXPECT_FALSE(guide[2].has_value());
}

}  // namespace
}  // namespace floorgrid
