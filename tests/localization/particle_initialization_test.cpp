// Where particles start: over the free space only, around a start with the asked spread, and,
// for global localization, on the best hypotheses of a lattice (the true pose first in a room
// without symmetry).
#include "floorgrid/localization/particle_initialization.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/localization/likelihood_field_model.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

TEST(FreeSpaceSampler, CandidatesAreTheFreeCellsAndSamplesLieInThem) {
  const OccupancyGrid grid = test::room_grid(test::asymmetric_room());
  const FreeSpaceSampler all(grid);
  EXPECT_EQ(all.cell_count(), grid.counts().free);
  EXPECT_NEAR(all.area(), static_cast<double>(grid.counts().free) * 0.0025, 1e-9);
  Random random(3);
  for (int k = 0; k < 2000; ++k) {
    int ix = 0, iy = 0;
    ASSERT_TRUE(grid.geometry().cell_of(all.sample_position(random), ix, iy));
    ASSERT_EQ(grid.state(ix, iy), CellState::free);
  }
  // Near the walls only: fewer cells, none in the free margin far outside.
  const FreeSpaceSampler near(grid, {.max_wall_distance = 0.5});
  EXPECT_LT(near.cell_count(), all.cell_count());
  int ix = 0, iy = 0;
  ASSERT_TRUE(grid.geometry().cell_of({6.0, 4.0}, ix, iy));  // mid-room, > 0.5 m from walls
  EXPECT_FALSE(near.is_candidate(ix, iy));
}

TEST(FreeSpaceSampler, AMapWithoutFreeSpaceIsRefused) {
  GridGeometry g;
  g.width = 10;
  g.height = 10;
  test::expect_input_error([&] { FreeSpaceSampler(OccupancyGrid(g, CellState::occupied)); },
                           {"'free_space'", "no free cell"});
}

TEST(SampleTrackingStart, ParticlesSpreadAsAskedAroundTheStart) {
  Random random(11);
  const TrackingStart start{.pose = {2.0, -1.0, 3.0},
                            .position_sigma = 0.3,
                            .heading_sigma = 0.2,
                            .scale = 1.05,
                            .scale_sigma = 0.01};
  const ParticleSet set = sample_tracking_start(start, 40000, random);
  ASSERT_EQ(set.size(), 40000u);
  ASSERT_TRUE(set.has_scale());
  double mx = 0, my = 0, vx = 0, ms = 0, dtheta2 = 0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    mx += set.x[i];
    my += set.y[i];
    ms += set.scale[i];
    const double d = normalize_angle(set.theta[i] - 3.0);
    dtheta2 += d * d;
    EXPECT_LE(std::abs(set.theta[i]), std::numbers::pi + 1e-12);
  }
  const double n = static_cast<double>(set.size());
  mx /= n, my /= n, ms /= n;
  for (std::size_t i = 0; i < set.size(); ++i)
    vx += (set.x[i] - mx) * (set.x[i] - mx);
  // Means within 4 standard errors, spreads within 3%.
  EXPECT_NEAR(mx, 2.0, 4 * 0.3 / std::sqrt(n));
  EXPECT_NEAR(my, -1.0, 4 * 0.3 / std::sqrt(n));
  EXPECT_NEAR(ms, 1.05, 4 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(vx / n), 0.3, 0.3 * 0.03);
  EXPECT_NEAR(std::sqrt(dtheta2 / n), 0.2, 0.2 * 0.03);
}

TEST(SampleGlobal, CoversTheFreeSpaceHeadingsAndScales) {
  const OccupancyGrid grid = test::room_grid(test::asymmetric_room());
  const FreeSpaceSampler free_space(grid);
  Random random(5);
  const ParticleSet set =
      sample_global(free_space, 5000, ScaleRange{.min = 0.9, .max = 1.2}, random);
  for (std::size_t i = 0; i < set.size(); ++i) {
    int ix = 0, iy = 0;
    ASSERT_TRUE(grid.geometry().cell_of({set.x[i], set.y[i]}, ix, iy));
    EXPECT_EQ(grid.state(ix, iy), CellState::free);
    EXPECT_GE(set.theta[i], -std::numbers::pi);
    EXPECT_LT(set.theta[i], std::numbers::pi);
    EXPECT_GE(set.scale[i], 0.9);
    EXPECT_LE(set.scale[i], 1.2);
  }
}

TEST(SeedBestHypotheses, TheTruePoseWinsInARoomWithoutSymmetry) {
  const VectorFloorplan room = test::asymmetric_room();
  const OccupancyGrid grid = test::room_grid(room);
  const LikelihoodFieldModel model(grid);
  const FreeSpaceSampler free_space(grid, {.max_wall_distance = 6.0});
  for (const Pose2& truth : {Pose2{2.5, 5.5, 0.4}, Pose2{9.0, 3.0, -2.0}}) {
    const RobotLog log = test::log_along(room, {truth});
    const ScanObservation scan = make_observation(log.scans[0], {.max_beams = 60});
    Random random(1);
    HypothesisSeedingOptions options;
    options.keep = 50;
    options.jitter = false;
    const HypothesisSeeding seeds =
        seed_best_hypotheses(free_space, scan, model, options, std::nullopt, random);
    ASSERT_EQ(seeds.particles.size(), 50u);
    // The best kept hypothesis is the lattice point nearest the truth (within half a step and
    // half a heading step).
    const Pose2 best = seeds.particles.pose(0);
    EXPECT_LT((best.translation() - truth.translation()).norm(), 0.2) << truth.x;
    EXPECT_LT(std::abs(normalize_angle(best.theta - truth.theta)), 0.05) << truth.x;
    EXPECT_GE(seeds.best_log_likelihood, seeds.worst_kept_log_likelihood);
  }
}

}  // namespace
}  // namespace floorgrid
