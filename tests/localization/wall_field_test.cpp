// The wall field against analytic walls: each cell's nearest wall point and normal, on a
// grid's occupied cells and on a vector plan's exact walls.
#include "floorgrid/localization/wall_field.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/maps/rasterize.hpp"

namespace floorgrid {
namespace {

/// One horizontal wall at y = 2 from x = 0 to 10, and a margin of free space around.
VectorFloorplan one_wall() {
  VectorFloorplan plan;
  plan.add_segment({0.0, 2.0}, {10.0, 2.0}, "W");
  return plan;
}

OccupancyGrid grid_of(const VectorFloorplan& plan) {
  RasterizeOptions options;
  options.wall_thickness = 0.05;
  options.margin = 2.0;
  return rasterize(plan, options);
}

TEST(WallField, VectorWallsGiveTheExactNearestPointAndNormal) {
  const VectorFloorplan plan = one_wall();
  const OccupancyGrid grid = grid_of(plan);
  const WallField field(plan, grid.geometry());
  for (const double x : {1.03, 4.5, 8.77}) {
    for (const double dy : {-0.4, -0.12, 0.07, 0.33}) {
      const WallPoint* w = field.nearest({x, 2.0 + dy});
      ASSERT_NE(w, nullptr) << x << " " << dy;
      // On the wall, within the cell of the query.
      EXPECT_NEAR(w->point.y(), 2.0, 1e-6);
      EXPECT_NEAR(w->point.x(), x, 0.05);
      EXPECT_NEAR(std::abs(w->normal.y()), 1.0, 1e-6);
      EXPECT_NEAR(w->normal.x(), 0.0, 1e-6);
    }
  }
  // Beyond max_distance (1 m) from every wall: no wall point.
  EXPECT_EQ(field.nearest({5.0, 3.5}), nullptr);
  EXPECT_EQ(field.nearest({-50.0, 2.0}), nullptr);  // off the grid
}

TEST(WallField, GridWallsGiveTheNearestOccupiedCellAndItsNormal) {
  const VectorFloorplan plan = one_wall();
  const OccupancyGrid grid = grid_of(plan);
  const WallField field(grid);
  for (const double dy : {-0.3, 0.2}) {
    const WallPoint* w = field.nearest({5.0, 2.0 + dy});
    ASSERT_NE(w, nullptr);
    // A cell centre of the drawn wall: within a cell of the true line.
    EXPECT_NEAR(w->point.y(), 2.0, grid.resolution());
    EXPECT_NEAR(std::abs(w->normal.y()), 1.0, 1e-3);
  }
}

TEST(WallField, ACornerHasNoClearNormal) {
  VectorFloorplan corner;
  corner.add_segment({0.0, 0.0}, {3.0, 0.0}, "W");
  corner.add_segment({0.0, 0.0}, {0.0, 3.0}, "W");
  const OccupancyGrid grid = grid_of(corner);
  const WallField field(grid);
  const WallPoint* w = field.nearest({0.01, 0.01});
  ASSERT_NE(w, nullptr);
  EXPECT_LT(w->normal.norm(), 1e-6) << "a corner's cell is matched point to point";
}

}  // namespace
}  // namespace floorgrid
