// Distance to a raster's wall surfaces, against the analytic distance to a stroke's edges.
#include "floorgrid/maps/wall_surface_field.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace floorgrid {
namespace {

// A stroke of cells 20 to 24 (5 cells of 0.1 m, occupied) across a 40 x 10 grid whose origin is
// turned by 0.3 rad: its surfaces lie at x = 2.0 and x = 2.5 m in the grid's frame.
OccupancyGrid stroke_grid() {
  GridGeometry g;
  g.width = 40;
  g.height = 10;
  g.resolution = 0.1;
  g.origin = Pose2{1.0, -2.0, 0.3};
  OccupancyGrid grid(g, CellState::free);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 20; ix < 25; ++ix)
      grid.set_state(ix, iy, CellState::occupied);
  }
  return grid;
}

Eigen::Vector2d at(const OccupancyGrid& grid, double x, double y) {
  return grid.geometry().origin.transform(Eigen::Vector2d(x, y));
}

TEST(WallSurfaceField, ZeroOnTheStrokesEdgesAndTheDistanceToThemElsewhere) {
  const OccupancyGrid grid = stroke_grid();
  const WallSurfaceField field(grid, 3.0);
  ASSERT_TRUE(field.has_walls());
  for (const double x : {0.73, 1.2, 1.96, 2.0, 2.04, 2.13, 2.25, 2.37, 2.5, 2.61, 3.3}) {
    const double expected = x < 2.25 ? std::abs(x - 2.0) : std::abs(x - 2.5);
    EXPECT_NEAR(field.distance(at(grid, x, 0.47)), expected, 1e-5) << x;
  }
}

TEST(WallSurfaceField, CentreLinesReadTheDistanceToTheCellsCentres) {
  const OccupancyGrid grid = stroke_grid();
  const WallSurfaceField field(grid, 3.0, WallSurfaceField::Line::centre);
  EXPECT_NEAR(field.distance(at(grid, 2.05, 0.55)), 0.0, 1e-5);
  EXPECT_NEAR(field.distance(at(grid, 2.25, 0.55)), 0.0, 1e-5);
  EXPECT_NEAR(field.distance(at(grid, 1.35, 0.55)), 0.7, 1e-5);
  EXPECT_NEAR(field.distance(at(grid, 3.15, 0.55)), 0.7, 1e-5);
}

TEST(WallSurfaceField, CappedOutsideTheGridAndWithoutWalls) {
  const OccupancyGrid grid = stroke_grid();
  const WallSurfaceField field(grid, 0.5);
  EXPECT_EQ(field.distance(at(grid, -1.0, 0.5)), 0.5);
  EXPECT_EQ(field.distance(at(grid, 0.2, 0.5)), 0.5);  // 1.8 m from the wall: capped
  const OccupancyGrid empty(grid.geometry(), CellState::free);
  const WallSurfaceField none(empty, 0.5);
  EXPECT_FALSE(none.has_walls());
  EXPECT_EQ(none.distance(at(grid, 2.0, 0.5)), 0.5);
}

}  // namespace
}  // namespace floorgrid
