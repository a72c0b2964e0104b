// The gridmap filter on a real log (FHW, from Radish) that loses itself now and then: restarted
// around its last converged pose, it is back within a few scans; restarted from the scan's best
// hypotheses over the whole map, it wandered the building's look-alike corridors for dozens.
#include <gtest/gtest.h>

#include "floorgrid/io/logs/carmen_log.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/pipeline/dual_maps.hpp"
#include "floorgrid/pipeline/gridmap_localization.hpp"
#include "floorgrid/robot/odometry_noise.hpp"
#include "floorgrid/simulation/log_dataset.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

struct Tracking {
  std::size_t scans = 0;  ///< after the first convergence
  std::size_t right = 0;  ///< of those: converged within 0.3 m of the truth
  std::size_t divergences = 0;
  DualLocalization::GridRestarts restarts;
};

/// The gridmap filter through the log, judged against the corrected poses.
Tracking localize(const LogDataset& d, const RobotLog& noisy, const DualLocalizerOptions& options) {
  const DualLocalizerInputs inputs{.plan = d.plan_raster, .gridmap = d.gridmap, .log = noisy};
  std::vector<std::string> notes;
  const DualMaps maps(inputs, options, notes);
  DualLocalization result;
  result.scans.resize(noisy.scans.size());
  for (std::size_t i = 0; i < result.scans.size(); ++i)
    result.scans[i].scan = i;
  const GridmapLocalization found = localize_on_gridmap(maps, inputs, options, result, {});
  Tracking run;
  if (!found.first_converged)
    return run;
  run.divergences = result.grid_divergences.total;
  run.restarts = result.grid_restarts;
  for (std::size_t i = *found.first_converged; i < result.scans.size(); ++i) {
    const FilterRecord& r = result.scans[i].grid;
    const double error = (r.pose.translation() - d.log.scans[i].robot_pose.translation()).norm();
    ++run.scans;
    run.right += r.converged && error < 0.3;
  }
  return run;
}

/// The FHW dataset of these tests and its run with SPEC's odometry noise.
struct FhwRun {
  LogDataset d;
  RobotLog noisy;
};

const FhwRun& fhw() {
  static const FhwRun run = [] {
    const io::CarmenLog log = io::read_carmen_log(test::data_path("carmen/fhw-corrected.log.gz"));
    LogDatasetOptions options;
    options.seed = 2;
    FhwRun r{simulate_from_log(log, options), {}};
    r.noisy = add_odometry_noise(r.d.log, {0.05, 0.01, 0.02, 0.05}, 2);
    return r;
  }();
  return run;
}

TEST(GridmapRestart, ALostFilterLooksNearItsLastPoseFirst) {
  const LogDataset& d = fhw().d;
  const RobotLog& noisy = fhw().noisy;

  const Tracking nearby = localize(d, noisy, {});
  DualLocalizerOptions global_only;
  global_only.gridmap_localization.restart_near_scans = 0;
  const Tracking global = localize(d, noisy, global_only);
  ASSERT_GT(nearby.scans, 400u);
  ASSERT_GE(global.divergences, 1u) << "the filter never lost itself: nothing to compare";
  EXPECT_EQ(global.restarts.near, 0u);
  EXPECT_EQ(global.restarts.global, global.divergences);
  EXPECT_GE(nearby.restarts.near, 1u);
  EXPECT_LE(nearby.restarts.near_failed, nearby.restarts.near);
  // Measured (2026-11-25): 426 and 406 of 484 scans, 3 and 4 divergences.
  EXPECT_GE(nearby.right, nearby.scans * 85 / 100) << nearby.right << " of " << nearby.scans;
  EXPECT_GT(nearby.right, global.right + 10) << global.right << " of " << global.scans;
}

// The other way round: where the gridmap filter is lost while the plan filter is sure, a
// gridmap filter started where the plan filter says takes over, and is right where it does.
TEST(GridmapRestart, ALostGridmapFilterIsRestartedWhereThePlanFilterIsSure) {
  const LogDataset& d = fhw().d;
  const DualLocalizerInputs inputs{.plan = d.plan_raster,
                                   .gridmap = d.gridmap,
                                   .log = fhw().noisy,
                                   .plan_scale = *d.options.plan_scale};
  // The run in which the gridmap filter loses itself for about 35 scans after 6 scans of
  // readings cut short (people close around the robot); the coarser lattice of earlier builds'
  // global localization gives that run.
  DualLocalizerOptions options;
  options.grid.filter.seeding.headings = 72;
  const DualLocalization mended = localize_dual(inputs, options, {});
  DualLocalizerOptions never = options;
  never.dual_check.mend_scans = 0;
  const DualLocalization plain = localize_dual(inputs, never, {});
  ASSERT_TRUE(mended.status.ok) << mended.status.message;
  ASSERT_TRUE(plain.status.ok) << plain.status.message;
  const auto right = [&](const FilterRecord& r, std::size_t i) {
    return r.converged &&
           (r.pose.translation() - d.log.scans[i].robot_pose.translation()).norm() < 0.3;
  };
  std::size_t mended_scans = 0, mended_right = 0, right_mended = 0, right_plain = 0;
  for (std::size_t i = 0; i < mended.scans.size(); ++i) {
    const ScanRecord& r = mended.scans[i];
    mended_scans += r.grid_mended;
    mended_right += r.grid_mended && right(r.grid, i);
    right_mended += right(r.grid, i);
    right_plain += right(plain.scans[i].grid, i);
  }
  EXPECT_EQ(plain.grid_restarts.from_plan, 0u);
  EXPECT_GE(mended.grid_restarts.from_plan, 1u);
  EXPECT_EQ(mended_scans, mended.grid_restarts.mended_scans);
  ASSERT_GE(mended_scans, 5u) << "nothing mended: nothing to judge";
  EXPECT_GE(mended_right, mended_scans * 9 / 10) << mended_right << " of " << mended_scans;
  // Measured (2026-11-26): 23 scans mended, all right; 451 scans right against 428.
  EXPECT_GT(right_mended, right_plain);
}

}  // namespace
}  // namespace floorgrid
