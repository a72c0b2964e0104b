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
