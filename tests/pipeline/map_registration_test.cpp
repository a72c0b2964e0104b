// The gridmap registered on the plan directly, checked against the simulator's exact warp over
// the whole scale range a plan of unknown resolution may have.
#include "floorgrid/pipeline/map_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid {
namespace {

const SimulatedDataset& office() {
  static const SimulatedDataset d = simulate("office", 2);
  return d;
}

// The office's plan drawn `factor` times too large, as a raster of a fixed number of cells per
// world metre (as a scanned drawing would be).
OccupancyGrid plan_raster(const SimulatedDataset& d, double factor) {
  RasterizeOptions options;
  options.resolution = 0.05 * factor;
  options.wall_thickness = 0.1 * factor;
  options.margin = 1.0 * factor;
  return rasterize(filter_layers(d.plan, {{"WALLS"}, {}}).scaled(factor), options);
}

// Mean distance, in world metres, between where the registration and the truth put the
// gridmap's occupied cells on the plan.
double registration_error(const MapSimilarity& t, const SimulatedDataset& d, double factor) {
  const PlanTruth truth(d.warp, d.plan_scale * factor);
  double sum = 0.0;
  int n = 0;
  const GridGeometry& g = d.gridmap.geometry();
  for (int iy = 0; iy < g.height; iy += 7) {
    for (int ix = 0; ix < g.width; ix += 7) {
      if (d.gridmap.state(ix, iy) != CellState::occupied)
        continue;
      const Eigen::Vector2d p = g.cell_center(ix, iy);
      const InverseResult exact = truth.grid_to_plan(p);
      sum += (t.apply(p) - exact.point).norm() / (d.plan_scale * factor);
      ++n;
    }
  }
  return sum / n;
}

TEST(MapRegistration, FindsScaleRotationAndPlaceOverTheWholeRange) {
  const SimulatedDataset& d = office();
  for (const double factor : {0.3, 1.0, 3.5}) {
    const MapRegistration r = register_maps(d.gridmap, plan_raster(d, factor));
    ASSERT_TRUE(r.found) << factor;
    const double true_scale = d.plan_scale * factor;  // plan metres per world metre
    EXPECT_NEAR(r.best.transform.scale / true_scale, 1.0, 0.005) << factor;
    EXPECT_LT(registration_error(r.best.transform, d, factor), 0.15) << factor;
    EXPECT_GT(r.best.on_walls, 0.5) << factor;
    EXPECT_LT(r.best.in_free_space, 0.05) << factor;
    EXPECT_GT(r.best.score, r.runner_up.score + 0.1) << factor;
  }
}

TEST(MapRegistration, AnotherBuildingsPlanScoresFarBelowTheRightOne) {
  const SimulatedDataset& d = office();
  const MapRegistration right = register_maps(d.gridmap, plan_raster(d, 1.0));
  const SimulatedDataset warehouse = simulate("warehouse", 1);
  RasterizeOptions options;
  const MapRegistration wrong =
      register_maps(d.gridmap, rasterize(filter_layers(warehouse.plan, {{"WALLS"}, {}}), options));
  ASSERT_TRUE(wrong.found);
  EXPECT_LT(wrong.best.score, 0.5 * right.best.score);
}

TEST(MapRegistration, MapsWithoutWallsFindNothing) {
  const SimulatedDataset& d = office();
  GridGeometry g;
  g.width = 50;
  g.height = 40;
  const OccupancyGrid empty(g, CellState::free);
  EXPECT_FALSE(register_maps(d.gridmap, empty).found);
  EXPECT_FALSE(register_maps(empty, plan_raster(d, 1.0)).found);
}

TEST(MapSimilarity, InverseUndoesApply) {
  MapSimilarity t;
  t.scale = 2.5;
  t.theta = 0.7;
  t.translation = {3.0, -4.0};
  const Eigen::Vector2d g(1.25, -7.5);
  EXPECT_LT((t.inverse(t.apply(g)) - g).norm(), 1e-12);
  const Pose2 pose = t.apply(Pose2{1.0, 2.0, 0.5});
  EXPECT_NEAR(pose.theta, 1.2, 1e-12);
}

}  // namespace
}  // namespace floorgrid
