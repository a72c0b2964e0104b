// The gridmap aligned to the plan from the two maps alone, checked against the simulator's
// exact warp: a bent building, a partial map, another building's plan, bad options.
#include "floorgrid/pipeline/map_alignment.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/maps/crop.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/plan_truth.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid {
namespace {

const SimulatedDataset& bent_office() {
  static const SimulatedDataset d = simulate("bent-office", 1);
  return d;
}

OccupancyGrid plan_grid(const SimulatedDataset& d) {
  return rasterize(filter_layers(d.plan, {{"WALLS"}, {}}), RasterizeOptions{});
}

// Each pair's grid point against where the truth puts its plan point, world metres.
std::vector<double> pair_errors(const ReferencePairs& pairs, const SimulatedDataset& d) {
  const PlanTruth truth(d.warp, d.plan_scale);
  std::vector<double> errors;
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    errors.push_back(
        (truth.plan_to_grid(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm());
  return errors;
}

// The registration's similarity alone at the same gridmap points: how far it puts them from
// where the truth does, world metres.
std::vector<double> similarity_errors(const MapAlignment& a, const SimulatedDataset& d) {
  const PlanTruth truth(d.warp, d.plan_scale);
  const MapSimilarity& s = a.registration.best.transform;
  std::vector<double> errors;
  for (Eigen::Index i = 0; i < a.pairs.size(); ++i) {
    const Eigen::Vector2d g = a.pairs.points_in_grid.col(i);
    errors.push_back((s.apply(g) - truth.grid_to_plan(g).point).norm() / s.scale);
  }
  return errors;
}

TEST(MapAlignment, BendsTheGridmapOntoTheWallsOfABentBuilding) {
  const SimulatedDataset& d = bent_office();
  const MapAlignment a = align_maps(d.gridmap, plan_grid(d), PlanWalls::vector_lines);
  ASSERT_TRUE(a.accepted) << a.diagnosis;
  EXPECT_GT(a.pairs.size(), 300);
  EXPECT_NEAR(a.registration.best.transform.scale / d.plan_scale, 1.0, 0.01);
  const double refined = upper_median(pair_errors(a.pairs, d));
  const double similar = upper_median(similarity_errors(a, d));
  // The bend is 0.3-1 m: no similarity fits it; the refinement follows it to centimetres.
  EXPECT_LT(refined, 0.08);
  EXPECT_LT(refined, 0.6 * similar) << "similarity alone " << similar;
  EXPECT_GT(a.fit.on_walls, 0.6);
  EXPECT_LT(a.fit.in_free_space, 0.05);
}

TEST(MapAlignment, ItsWarpFollowsTheTruthBothWaysWithItsScale) {
  const SimulatedDataset& d = bent_office();
  const MapAlignment a = align_maps(d.gridmap, plan_grid(d), PlanWalls::vector_lines);
  ASSERT_TRUE(a.accepted && a.warp);
  const PlanTruth truth(d.warp, d.plan_scale);
  std::vector<double> errors, round_trips, headings;
  for (Eigen::Index i = 0; i < a.pairs.size(); i += 7) {
    const Eigen::Vector2d g = a.pairs.points_in_grid.col(i);
    const Eigen::Vector2d p = a.warp->apply(g);
    errors.push_back((p - truth.grid_to_plan(g).point).norm() / d.plan_scale);
    round_trips.push_back((a.warp->inverse(p) - g).norm());
    // A pose's heading turns as the warp turns the space around it.
    const Pose2 pose{g.x(), g.y(), 0.3};
    const Pose2 back = a.warp->inverse(a.warp->apply(pose));
    headings.push_back(std::abs(normalize_angle(back.theta - pose.theta)));
  }
  // Nearer the truth than the similarity alone (its pairs, projected onto their walls, nearer
  // still: above).
  EXPECT_LT(upper_median(errors), 0.1);
  EXPECT_LT(upper_median(errors), 0.75 * upper_median(similarity_errors(a, d)));
  EXPECT_LT(*std::max_element(round_trips.begin(), round_trips.end()), 1e-6);
  EXPECT_LT(*std::max_element(headings.begin(), headings.end()), 1e-6);
  // Its scale is the plan's, within the bend's strain (1.5% on a bent office); world metres
  // per plan metre, as floorplan_scale.
  EXPECT_NEAR(a.scale.scale * d.plan_scale, 1.0, 0.015);
  EXPECT_NEAR(a.scale.similarity_scale * d.plan_scale, 1.0, 0.015);
  EXPECT_GT(a.scale.relative_std, 0.0);
  EXPECT_LT(a.scale.relative_std, 0.02);
}

TEST(MapAlignment, TheScaleOfASimilarityWarpIsItsOwn) {
  MapWarp warp;
  warp.similarity = {.scale = 0.8, .theta = 0.4, .translation = {3.0, -2.0}};
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 50; ++i)
    points.emplace_back(0.37 * i, std::sin(0.3 * i) * 5.0);
  const WarpScale s = warp_scale(warp, points);
  EXPECT_NEAR(s.scale, 1.25, 1e-9);
  EXPECT_NEAR(s.similarity_scale, 1.25, 1e-9);
  EXPECT_NEAR(s.relative_std, 0.0, 1e-9);
  const Pose2 pose{1.0, 2.0, 0.5};
  const Pose2 mapped = warp.apply(pose);
  EXPECT_NEAR(mapped.theta, 0.9, 1e-9);
  EXPECT_NEAR((mapped.translation() - warp.similarity.apply(pose.translation())).norm(), 0.0,
              1e-12);
}

TEST(MapAlignment, APartOfTheBuildingFindsItsPlace) {
  const SimulatedDataset& d = bent_office();
  const GridGeometry& g = d.gridmap.geometry();
  const OccupancyGrid part = crop(d.gridmap, {0, 0, g.width / 2, g.height});
  const MapAlignment a = align_maps(part, plan_grid(d), PlanWalls::vector_lines);
  ASSERT_TRUE(a.accepted) << a.diagnosis;
  EXPECT_LT(upper_median(pair_errors(a.pairs, d)), 0.08);
}

TEST(MapAlignment, AnotherBuildingsPlanFitsFarWorse) {
  const SimulatedDataset& d = bent_office();
  const SimulatedDataset warehouse = simulate("warehouse", 1);
  const MapAlignment right = align_maps(d.gridmap, plan_grid(d), PlanWalls::vector_lines);
  const MapAlignment wrong = align_maps(d.gridmap, plan_grid(warehouse), PlanWalls::vector_lines);
  EXPECT_FALSE(wrong.accepted);
  EXPECT_FALSE(wrong.diagnosis.empty());
  EXPECT_LT(wrong.fit.score, 0.5 * right.fit.score);
}

// The grid twice, side by side with a gap of `gap` cells: a building with two identical wings.
OccupancyGrid twice(const OccupancyGrid& grid, int gap) {
  GridGeometry g = grid.geometry();
  g.width = 2 * grid.width() + gap;
  OccupancyGrid out(g);
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      out.set_state(ix, iy, grid.state(ix, iy));
      out.set_state(ix + grid.width() + gap, iy, grid.state(ix, iy));
    }
  }
  return out;
}

TEST(MapAlignment, TwoPlacesThatFitAlikeAreNotAnAnswer) {
  const SimulatedDataset& d = bent_office();
  const OccupancyGrid plan = plan_grid(d);
  const MapAlignment one = align_maps(d.gridmap, plan, PlanWalls::vector_lines);
  ASSERT_TRUE(one.accepted) << one.diagnosis;
  // The right place beats every other the registration found, bent too (measured: 0.61).
  EXPECT_LT(one.ambiguity, 0.75);
  const MapAlignment two = align_maps(d.gridmap, twice(plan, 40), PlanWalls::vector_lines);
  EXPECT_FALSE(two.accepted);
  EXPECT_GE(two.fit.score, 0.9 * one.fit.score);  // it fits: the fitness alone would pass it
  ASSERT_TRUE(two.runner_up.has_value());
  EXPECT_GT(two.ambiguity, 0.9);
  EXPECT_NE(two.diagnosis.find("another place fits about as well"), std::string::npos)
      << two.diagnosis;
  // The two answers are the two wings: a wing's width apart, at the same scale and turn.
  const MapSimilarity& a = two.registration.best.transform;
  const MapSimilarity& b = two.runner_up->start;
  const double wing = (plan.width() + 40) * plan.resolution();
  EXPECT_NEAR(std::abs((a.translation - b.translation).x()), wing, 0.5);
  EXPECT_NEAR(a.scale / b.scale, 1.0, 0.01);
}

TEST(MapAlignment, BadOptionsNameTheirField) {
  MapAlignmentOptions o;
  o.last_spacing = 20.0;
  try {
    validate(o);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("align.maps_only.last_spacing"), std::string::npos);
  }
  o = {};
  o.max_normal_angle = 0.0;
  EXPECT_THROW(validate(o), InputError);
  MapRegistrationOptions r;
  r.correlation.cell = -1.0;
  try {
    validate(r);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("map_registration.correlation.cell"), std::string::npos);
  }
}

}  // namespace
}  // namespace floorgrid
