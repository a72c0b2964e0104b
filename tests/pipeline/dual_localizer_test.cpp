// The dual localization on a simulated building, run through the library: a wrong start is
// caught, NaN readings are harmless, and the plan is found without any start.
#include "floorgrid/pipeline/dual_localizer.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/simulation/simulator.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// The simulated office (seed 1) as a dataset read back from disk, shared by the tests.
const io::LoadedDataset& office() {
  static const test::TempDir dir;
  static const io::LoadedDataset dataset = [] {
    io::write_simulated_dataset(simulate("office", 1), dir.path(), false);
    return io::load_dataset(dir.path());
  }();
  return dataset;
}

StartPoses manifest_start(const io::LoadedDataset& d) {
  return {d.manifest.initial_pose->plan, d.manifest.initial_pose->grid};
}

/// Median of |truth(plan endpoint) - grid endpoint| over the pairs.
double median_pair_error(const io::LoadedDataset& d, const ReferencePairs& pairs) {
  std::vector<double> e;
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    e.push_back(
        (d.truth_warp->plan_to_grid(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i))
            .norm());
  std::nth_element(e.begin(), e.begin() + static_cast<long>(e.size() / 2), e.end());
  return e.empty() ? std::numeric_limits<double>::infinity() : e[e.size() / 2];
}

/// The first `n` scans of a log (a shorter run keeps these tests quick).
RobotLog first_scans(const RobotLog& log, std::size_t n) {
  RobotLog out = log;
  out.scans.resize(std::min(n, out.scans.size()));
  return out;
}

TEST(DualLocalizer, WrongStartIsDetectedAsDivergenceAndPairsWaitForRecovery) {
  const io::LoadedDataset& d = office();
  const RobotLog& log = *d.log;
  StartPoses start = manifest_start(d);
  // The gridmap filter starts 3 m and 90 degrees off.
  start.grid = start.grid.compose({3.0, 0.0, 1.57});
  const DualLocalization r = localize_dual({.plan = d.plan_grid,
                                            .gridmap = d.gridmap,
                                            .log = log,
                                            .start = start,
                                            .plan_scale = d.manifest.floorplan_scale,
                                            .plan_geometry = &*d.plan});
  ASSERT_TRUE(r.status.ok) << r.status.message;
  EXPECT_GE(r.grid_divergences.total, 1u) << "the wrong start was not caught";
  // No scan makes pairs before the gridmap filter has found itself again, and the scans with
  // pairs are all after its recovery.
  ASSERT_GT(r.grid_start_scan, 0u);
  for (const ScanRecord& s : r.scans) {
    if (s.scan < r.grid_start_scan) {
      EXPECT_FALSE(s.grid.converged) << s.scan;
      EXPECT_EQ(s.pairs, 0u) << s.scan;
    }
  }
  EXPECT_GT(r.pairs.size(), 1000);
  EXPECT_LE(median_pair_error(d, r.pairs), 0.05);
}

TEST(DualLocalizer, NanReadingsAreSkippedNotPaired) {
  const io::LoadedDataset& d = office();
  RobotLog log = first_scans(*d.log, 400);
  for (std::size_t i = 0; i < log.scans.size(); i += 3)
    for (std::size_t k = 0; k < log.scans[i].ranges.size(); k += 5)
      log.scans[i].ranges[k] = std::numeric_limits<float>::quiet_NaN();
  const DualLocalization r = localize_dual({.plan = d.plan_grid,
                                            .gridmap = d.gridmap,
                                            .log = log,
                                            .start = manifest_start(d),
                                            .plan_scale = d.manifest.floorplan_scale,
                                            .plan_geometry = &*d.plan});
  ASSERT_GT(r.pairs.size(), 100);
  EXPECT_TRUE(r.pairs.points_in_plan.allFinite());
  EXPECT_TRUE(r.pairs.points_in_grid.allFinite());
  EXPECT_GT(r.rejections.no_return, 0u);
  EXPECT_LE(median_pair_error(d, r.pairs), 0.05);
}

TEST(DualLocalizer, FindsBothStartsAndTheScaleWithoutAnyStart) {
  const io::LoadedDataset& d = office();
  const RobotLog log = first_scans(*d.log, 1200);
  const DualLocalization r = localize_dual(
      {.plan = d.plan_grid, .gridmap = d.gridmap, .log = log, .plan_geometry = &*d.plan});
  // The start comes from the direct registration of the two maps when it is clear, else from
  // the registration of the run's submap on the plan.
  const bool from_maps = std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
    return n.find("gridmap registered on the plan") != std::string::npos;
  });
  ASSERT_TRUE(r.registration.has_value() || from_maps);
  // The two starts found are the same place: the exact warp takes the plan start onto the
  // gridmap start.
  const Eigen::Vector2d implied = d.truth_warp->plan_to_grid(r.start.plan.translation());
  EXPECT_LT((implied - r.start.grid.translation()).norm(), 0.5);
  EXPECT_TRUE(r.plan_scale_estimated);
  EXPECT_NEAR(r.plan_scale, 1.0 / d.truth_warp->plan_scale(), 0.003);
  EXPECT_GE(r.converged_fraction, 0.8);
  EXPECT_LE(median_pair_error(d, r.pairs), 0.05);
}

TEST(DualLocalizer, RejectsTooShortLogsBadScalesAndLogsWithoutReturns) {
  const io::LoadedDataset& d = office();
  const RobotLog one = first_scans(*d.log, 1);
  EXPECT_THROW(localize_dual({.plan = d.plan_grid, .gridmap = d.gridmap, .log = one}), InputError);
  const RobotLog ten = first_scans(*d.log, 10);
  EXPECT_THROW(
      localize_dual({.plan = d.plan_grid, .gridmap = d.gridmap, .log = ten, .plan_scale = -1.0}),
      InputError);
  RobotLog blind = ten;
  for (LaserScan& scan : blind.scans)
    std::fill(scan.ranges.begin(), scan.ranges.end(), std::numeric_limits<float>::quiet_NaN());
  try {
    localize_dual({.plan = d.plan_grid, .gridmap = d.gridmap, .log = blind});
    ADD_FAILURE() << "a log without returns was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "log");
  }
}

TEST(DualLocalizer, AGridmapFilterThatNeverConvergesIsReportedNotThrown) {
  const io::LoadedDataset& d = office();
  // The gridmap at a hundredth of its resolution: nothing of the run fits it.
  GridGeometry geometry = d.gridmap.geometry();
  geometry.resolution *= 100.0;
  OccupancyGrid wrong(geometry);
  for (int iy = 0; iy < geometry.height; ++iy)
    for (int ix = 0; ix < geometry.width; ++ix)
      wrong.set_state(ix, iy, d.gridmap.state(ix, iy));
  const RobotLog log = first_scans(*d.log, 30);
  DualLocalizerOptions options;
  options.gridmap_localization.max_global_scans = 20;
  for (const bool with_start : {false, true}) {
    const DualLocalization r = localize_dual(
        {.plan = d.plan_grid,
         .gridmap = wrong,
         .log = log,
         .start = with_start ? std::optional<StartPoses>(manifest_start(d)) : std::nullopt,
         .plan_geometry = &*d.plan},
        options);
    EXPECT_FALSE(r.status.ok);
    EXPECT_EQ(r.pairs.size(), 0);
    EXPECT_NE(r.status.message.find("did not converge within 20 scans"), std::string::npos)
        << r.status.message;
    // With a start, the message blames the start, not the lack of one.
    EXPECT_EQ(r.status.field, with_start ? "initial_pose" : "gridmap");
    EXPECT_EQ(r.status.message.find("or give initial_pose") == std::string::npos, with_start)
        << r.status.message;
  }
}

}  // namespace
}  // namespace floorgrid
