// The plan as a robot inside sees it: of a wall drawn as two lines, only the face towards the
// room is kept; a plan without a closed inside is left as it is.
#include "floorgrid/maps/visible_walls.hpp"

#include <gtest/gtest.h>

#include "floorgrid/maps/rasterize.hpp"

namespace floorgrid {
namespace {

OccupancyGrid raster(const VectorFloorplan& plan) {
  RasterizeOptions options;
  options.wall_thickness = 0.05;
  options.margin = 1.0;
  return rasterize(plan, options);
}

void rectangle(VectorFloorplan& plan, double x0, double y0, double x1, double y1) {
  plan.add_segment({x0, y0}, {x1, y0}, "W");
  plan.add_segment({x1, y0}, {x1, y1}, "W");
  plan.add_segment({x1, y1}, {x0, y1}, "W");
  plan.add_segment({x0, y1}, {x0, y0}, "W");
}

CellState state_at(const OccupancyGrid& grid, double x, double y) {
  int ix = 0, iy = 0;
  EXPECT_TRUE(grid.geometry().cell_of({x, y}, ix, iy));
  return grid.state(ix, iy);
}

TEST(VisibleWalls, TheOuterFaceOfAWallDrawnAsTwoLinesIsDropped) {
  // A 10 m x 8 m room whose outline is drawn twice, 0.3 m apart (a wall's two faces).
  VectorFloorplan plan;
  rectangle(plan, 0.0, 0.0, 10.0, 8.0);
  rectangle(plan, 0.3, 0.3, 9.7, 7.7);
  const OccupancyGrid grid = raster(plan);
  const VisibleWalls visible = visible_walls(grid);
  ASSERT_TRUE(visible.applied);
  EXPECT_GT(visible.hidden, 0u);
  EXPECT_LT(visible.hidden, visible.walls);
  // The inner face (towards the room) stays a wall, the outer face is hidden.
  EXPECT_EQ(state_at(visible.grid, 5.0, 0.3), CellState::occupied);
  EXPECT_EQ(state_at(visible.grid, 5.0, 0.0), CellState::unknown);
  EXPECT_EQ(state_at(visible.grid, 0.0, 4.0), CellState::unknown);
  EXPECT_EQ(state_at(visible.grid, 9.7, 4.0), CellState::occupied);
  // The room is free space a robot can reach: about 9.4 m x 7.4 m of cells.
  const double room_area = static_cast<double>(visible.room_cells) * 0.05 * 0.05;
  EXPECT_NEAR(room_area, 9.4 * 7.4, 2.0);
}

TEST(VisibleWalls, WallsFarFromEveryRoomStay) {
  // The room of the first test, and 3 m beside it a corridor 1.5 m wide drawn open at both
  // ends: the outside floods it, yet the robot walks there and sees its walls.
  VectorFloorplan plan;
  rectangle(plan, 0.0, 0.0, 10.0, 8.0);
  rectangle(plan, 0.3, 0.3, 9.7, 7.7);
  plan.add_segment({13.0, -2.0}, {13.0, 12.0}, "W");
  plan.add_segment({14.5, -2.0}, {14.5, 12.0}, "W");
  const OccupancyGrid grid = raster(plan);
  const VisibleWalls visible = visible_walls(grid);
  ASSERT_TRUE(visible.applied);
  EXPECT_EQ(state_at(visible.grid, 13.0, 5.0), CellState::occupied);
  EXPECT_EQ(state_at(visible.grid, 14.5, 5.0), CellState::occupied);
  // The room's outer face still goes.
  EXPECT_EQ(state_at(visible.grid, 10.0, 4.0), CellState::unknown);
  // Hiding everything beyond reach of a room (the old rule) took the corridor's walls.
  VisibleWallsOptions all;
  all.max_thickness = 1e9;
  EXPECT_EQ(state_at(visible_walls(grid, all).grid, 13.0, 5.0), CellState::unknown);
}

TEST(VisibleWalls, APlanWithoutAClosedInsideIsLeftAsItIs) {
  VectorFloorplan plan;
  plan.add_segment({0.0, 0.0}, {10.0, 0.0}, "W");
  plan.add_segment({0.0, 3.0}, {10.0, 3.0}, "W");
  const OccupancyGrid grid = raster(plan);
  const VisibleWalls visible = visible_walls(grid);
  EXPECT_FALSE(visible.applied);
  EXPECT_EQ(visible.hidden, 0u);
}

}  // namespace
}  // namespace floorgrid
