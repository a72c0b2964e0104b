// Which pairs align goes on with: the run's judged on their own (plan match, scans, coverage of
// the gridmap's walls) and against the maps' bent map, on made-up pairs and maps whose answer
// is known.
#include "floorgrid/pipeline/pair_sources.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

// A 20 x 10 m box of walls, 0.05 m cells, the rest free.
OccupancyGrid box_map() {
  GridGeometry g;
  g.width = 400;
  g.height = 200;
  g.resolution = 0.05;
  OccupancyGrid grid(g, CellState::free);
  for (int x = 0; x < g.width; ++x) {
    grid.set_state(x, 0, CellState::occupied);
    grid.set_state(x, g.height - 1, CellState::occupied);
  }
  for (int y = 0; y < g.height; ++y) {
    grid.set_state(0, y, CellState::occupied);
    grid.set_state(g.width - 1, y, CellState::occupied);
  }
  return grid;
}

// Pairs on the box's walls between x0 and x1 (grid metres), plan = grid * plan_per_world.
ReferencePairs wall_pairs(double x0, double x1, double plan_per_world,
                          const Eigen::Vector2d& plan_shift = Eigen::Vector2d::Zero()) {
  std::vector<Eigen::Vector2d> grid;
  for (double x = x0; x <= x1; x += 0.25) {
    grid.emplace_back(x, 0.025);
    grid.emplace_back(x, 9.975);
  }
  ReferencePairs p;
  p.points_in_grid.resize(2, static_cast<Eigen::Index>(grid.size()));
  p.points_in_plan.resize(2, static_cast<Eigen::Index>(grid.size()));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    p.points_in_grid.col(static_cast<Eigen::Index>(i)) = grid[i];
    p.points_in_plan.col(static_cast<Eigen::Index>(i)) = plan_per_world * grid[i] + plan_shift;
  }
  return p;
}

// The maps' alignment: accepted, its warp the similarity plan = grid * plan_per_world.
MapAlignment maps_of(double plan_per_world, bool accepted = true) {
  MapAlignment m;
  m.accepted = accepted;
  m.warp = MapWarp{};
  m.warp->similarity.scale = plan_per_world;
  m.scale = {1.0 / plan_per_world, 0.005, 1.0 / plan_per_world};
  m.pairs = wall_pairs(0.0, 20.0, plan_per_world);
  m.diagnosis = accepted ? "" : "no fit";
  return m;
}

PlanMatch match_scoring(double score) {
  PlanMatch m;
  m.judged = true;
  m.score.score = score;
  return m;
}

RunPairsSummary run_of(const ReferencePairs& pairs, double plan_scale, std::size_t pair_scans,
                       double match = 0.6) {
  return {.localized = true,
          .failure = "",
          .pairs = &pairs,
          .plan_scale = plan_scale,
          .noise_m = 0.05,
          .pair_scans = pair_scans,
          .scans = 1000,
          .match = match_scoring(match),
          .match_accepted = match >= 0.15};
}

const auto judge_maps_at = [](double score) {
  return [score](const ReferencePairs&) { return match_scoring(score); };
};

TEST(PairSources, WhatThePairsOfAPlaceShareIsTheirMeanDisagreementNotTheirNoise) {
  const OccupancyGrid map = box_map();
  const MapAlignment maps = maps_of(0.5);
  // Every run pair 0.1 m (world) off the maps' along x, and half of them 0.3 m further each way
  // in y, alternately: each pair lies about 0.32 m from the maps, the places' means 0.1 m.
  ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5);
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    const double y = (i / 2) % 2 == 0 ? 0.3 : -0.3;
    pairs.points_in_plan.col(i) += 0.5 * Eigen::Vector2d(0.1, y);
  }
  const PairSourceCheck c =
      check_pair_sources(run_of(pairs, 2.0, 500), &maps, map, {}, judge_maps_at(0.9));
  ASSERT_TRUE(c.compared);
  EXPECT_NEAR(c.disagreement_median_m, std::hypot(0.1, 0.3), 1e-9);
  EXPECT_NEAR(c.disagreement_local_median_m, 0.1, 1e-9);
  // Cells as small as a pair apart keep each pair alone: the mean is the pair.
  PairSourceOptions fine;
  fine.bias_cell = 0.01;
  EXPECT_NEAR(check_pair_sources(run_of(pairs, 2.0, 500), &maps, map, fine, judge_maps_at(0.9))
                  .disagreement_local_median_m,
              std::hypot(0.1, 0.3), 1e-9);
  fine.bias_cell = 0.0;
  test::expect_input_error([&] { validate(fine); }, {"align.sources.bias_cell"});
}

TEST(PairSources, CoverageIsTheShareOfWallsNearAPair) {
  const OccupancyGrid map = box_map();
  // Pairs along the two long walls cover them and the end walls' 2 m next to them: 956 of the
  // box's 1196 wall cells; along their left quarter, the first 7 m of the long walls and the
  // left end wall's ends: 360.
  EXPECT_NEAR(wall_coverage(map, wall_pairs(0.0, 20.0, 1.0).points_in_grid, 2.0), 0.80, 0.02);
  const double quarter = wall_coverage(map, wall_pairs(0.0, 5.0, 1.0).points_in_grid, 2.0);
  EXPECT_NEAR(quarter, 0.30, 0.02);
  EXPECT_EQ(wall_coverage(map, Eigen::Matrix2Xd(2, 0), 2.0), 0.0);
}

TEST(PairSources, TheRunsPairsAreUsedWhenTheyPassAndAgree) {
  const OccupancyGrid map = box_map();
  const ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  const PairSourceCheck c =
      check_pair_sources(run_of(pairs, 2.0, 500), &maps, map, {}, judge_maps_at(0.9));
  EXPECT_TRUE(c.run_accepted) << c.run_failure;
  EXPECT_TRUE(c.compared);
  EXPECT_TRUE(c.agree);
  EXPECT_NEAR(c.disagreement_median_m, 0.0, 1e-9);
  EXPECT_EQ(c.chosen, "run");
  EXPECT_TRUE(c.fallback.empty());
  EXPECT_EQ(c.fill.size(), 0);  // the run reached every wall the maps' pairs are on
}

TEST(PairSources, TheMapsFillWhereTheRunDidNotReach) {
  const OccupancyGrid map = box_map();
  const ReferencePairs pairs = wall_pairs(0.0, 12.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  const PairSourceCheck c =
      check_pair_sources(run_of(pairs, 2.0, 500), &maps, map, {}, judge_maps_at(0.9));
  ASSERT_EQ(c.chosen, "run");
  ASSERT_GT(c.fill.size(), 0);
  for (Eigen::Index i = 0; i < c.fill.size(); ++i)
    EXPECT_GT(c.fill.points_in_grid(0, i), 14.0 - 1e-9);  // beyond 12 m + the 2 m radius
}

TEST(PairSources, AFewScansCannotVouchForTheBuilding) {
  const OccupancyGrid map = box_map();
  const ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  PairSourceCheck c = check_pair_sources(run_of(pairs, 2.0, 5), &maps, map, {}, judge_maps_at(0.9));
  EXPECT_FALSE(c.run_accepted);
  EXPECT_NE(c.run_failure.find("5 of 1000 scans"), std::string::npos) << c.run_failure;
  EXPECT_EQ(c.chosen, "maps");
  EXPECT_EQ(c.fallback, c.run_failure);
  // Neither: none.
  const MapAlignment refused = maps_of(0.5, false);
  c = check_pair_sources(run_of(pairs, 2.0, 5), &refused, map, {}, judge_maps_at(0.9));
  EXPECT_EQ(c.chosen, "none");
  // The maps accepted on their own but failing the plan-match check the run is held to: none,
  // and why.
  const auto above_095 = [](const PlanMatch& m) { return m.score.score >= 0.95; };
  c = check_pair_sources(run_of(pairs, 2.0, 5), &maps, map, {}, judge_maps_at(0.9), above_095);
  EXPECT_EQ(c.chosen, "none");
  EXPECT_TRUE(c.fallback.empty());
  EXPECT_NE(c.maps_failure.find("plan match 0.90"), std::string::npos) << c.maps_failure;
  c = check_pair_sources(run_of(pairs, 2.0, 5), &maps, map, {}, judge_maps_at(0.96), above_095);
  EXPECT_EQ(c.chosen, "maps");
}

TEST(PairSources, ARunThatFitsTheGridmapForAThirdOfItsScansCannotVouch) {
  // As with a gridmap whose resolution was given wrong: the filters converge where it happens
  // to fit, and the pairs from there cover the walls and agree with the maps.
  const OccupancyGrid map = box_map();
  const ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  RunPairsSummary run = run_of(pairs, 2.0, 500);
  run.converged_fraction = 0.37;
  PairSourceCheck c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.9));
  EXPECT_FALSE(c.run_accepted);
  EXPECT_NE(c.run_failure.find("converged on 37% of the scans"), std::string::npos)
      << c.run_failure;
  EXPECT_EQ(c.chosen, "maps");
  run.converged_fraction = 0.5;
  c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.9));
  EXPECT_TRUE(c.run_accepted);
}

TEST(PairSources, PairsCoveringLittleOfTheWallsAreNotEnough) {
  const OccupancyGrid map = box_map();
  const ReferencePairs pairs = wall_pairs(0.0, 1.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  const PairSourceCheck c =
      check_pair_sources(run_of(pairs, 2.0, 500), &maps, map, {}, judge_maps_at(0.9));
  EXPECT_FALSE(c.run_accepted);
  EXPECT_LT(c.coverage, 0.2);
  EXPECT_NE(c.run_failure.find("cover"), std::string::npos) << c.run_failure;
  EXPECT_EQ(c.chosen, "maps");
}

TEST(PairSources, WhenTheyDisagreeThePlanMatchDecides) {
  const OccupancyGrid map = box_map();
  // The run's pairs 3 m off along the walls from where the maps put them.
  const ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5, {1.5, 0.0});
  const MapAlignment maps = maps_of(0.5);
  PairSourceCheck c =
      check_pair_sources(run_of(pairs, 2.0, 500, 0.5), &maps, map, {}, judge_maps_at(0.8));
  EXPECT_TRUE(c.compared);
  EXPECT_FALSE(c.agree);
  EXPECT_NEAR(c.disagreement_median_m, 3.0, 1e-9);
  EXPECT_EQ(c.chosen, "maps");
  EXPECT_NE(c.fallback.find("disagree"), std::string::npos) << c.fallback;
  // A tie (within the margin) goes to the maps: a run can slide along a corridor and match the
  // plan as well under one similarity.
  c = check_pair_sources(run_of(pairs, 2.0, 500, 0.5), &maps, map, {}, judge_maps_at(0.49));
  EXPECT_EQ(c.chosen, "maps");
  // The run's clearly better: the run's.
  c = check_pair_sources(run_of(pairs, 2.0, 500, 0.5), &maps, map, {}, judge_maps_at(0.47));
  EXPECT_EQ(c.chosen, "run");
  EXPECT_TRUE(c.fallback.empty());
  // A negative margin keeps the run's pairs up to that much below the maps'.
  PairSourceOptions favour_run;
  favour_run.run_match_margin = -0.05;
  c = check_pair_sources(run_of(pairs, 2.0, 500, 0.5), &maps, map, favour_run, judge_maps_at(0.53));
  EXPECT_EQ(c.chosen, "run");
  c = check_pair_sources(run_of(pairs, 2.0, 500, 0.5), &maps, map, favour_run, judge_maps_at(0.56));
  EXPECT_EQ(c.chosen, "maps");
}

TEST(PairSources, HowFarTheWallsFacesMovedTheRunsScaleWidensTheScaleTolerance) {
  const OccupancyGrid map = box_map();
  // The pairs where the maps put them, but the run's scale 2.6% above the maps' (beyond the
  // 2% floor of the scale tolerance), as on HIH's thin-stroked drawing: the run fitted the
  // walls' faces in front of the ink, the maps' registration met them on the ink.
  const ReferencePairs pairs = wall_pairs(0.0, 20.0, 0.5);
  const MapAlignment maps = maps_of(0.5);
  RunPairsSummary run = run_of(pairs, 2.0 * 1.026, 500, 0.5);
  PairSourceCheck c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.5));
  EXPECT_NEAR(c.scale_tolerance, 2.0 * 0.02, 1e-12);
  EXPECT_EQ(c.run_scale_at_drawn_walls, 0.0);
  EXPECT_FALSE(c.agree);
  EXPECT_EQ(c.chosen, "maps");
  // Without the faces' offset the run's scale came out 1.5% above the maps': the faces moved it
  // by 1.1% of 2, which the maps' may be off by too. They agree; the run's pairs are used.
  run.scale_at_drawn_walls = 2.0 * 1.015;
  c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.5));
  EXPECT_NEAR(c.scale_tolerance, 2.0 * (0.02 + 0.011), 1e-12);
  EXPECT_NEAR(c.run_scale_at_drawn_walls, 2.0 * 1.015, 1e-12);
  EXPECT_TRUE(c.agree);
  EXPECT_EQ(c.chosen, "run");
  // Moved by 0.3% only, the 2.6% stays a disagreement.
  run.scale_at_drawn_walls = 2.0 * 1.023;
  c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.5));
  EXPECT_FALSE(c.agree);
  EXPECT_EQ(c.chosen, "maps");
}

TEST(PairSources, ARunThatFailedFallsBackOnTheMaps) {
  const OccupancyGrid map = box_map();
  const MapAlignment maps = maps_of(0.5);
  RunPairsSummary run;
  run.localized = false;
  run.failure = "the gridmap filter never converged";
  run.pairs = nullptr;
  const PairSourceCheck c = check_pair_sources(run, &maps, map, {}, judge_maps_at(0.9));
  EXPECT_EQ(c.chosen, "maps");
  EXPECT_EQ(c.fallback, run.failure);
}

TEST(PairSources, BadOptionsNameTheirField) {
  PairSourceOptions o;
  o.min_coverage = 1.5;
  test::expect_input_error([&] { validate(o); }, {"align.sources.min_coverage"});
  // The margin's range is the scores' own, as `floorgrid config` documents it.
  o = {};
  o.run_match_margin = -0.1;
  EXPECT_NO_THROW(validate(o));
  o.run_match_margin = 1.5;
  test::expect_input_error([&] { validate(o); }, {"align.sources.run_match_margin", "[-1, 1]"});
}

}  // namespace
}  // namespace floorgrid
