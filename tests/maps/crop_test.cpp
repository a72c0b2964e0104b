#include "floorgrid/maps/crop.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace floorgrid {
namespace {

/// A 100 x 80 grid at 0.1 m, turned by 0.3 rad about an origin at (5, -2), unknown but for a
/// block of free cells with one occupied cell.
OccupancyGrid sparse_grid() {
  GridGeometry g;
  g.width = 100;
  g.height = 80;
  g.resolution = 0.1;
  g.origin = {5.0, -2.0, 0.3};
  OccupancyGrid grid(g);
  for (int iy = 30; iy < 45; ++iy)
    for (int ix = 20; ix < 60; ++ix)
      grid.set_state(ix, iy, CellState::free);
  grid.set_cell(25, 40, CellState::occupied, 87);
  return grid;
}

TEST(Crop, KnownBoxIsTheKnownCellsGrownByTheMargin) {
  const OccupancyGrid grid = sparse_grid();
  const CellBox tight = known_cells_box(grid, 0);
  EXPECT_EQ(tight.x0, 20);
  EXPECT_EQ(tight.y0, 30);
  EXPECT_EQ(tight.x1, 60);
  EXPECT_EQ(tight.y1, 45);
  const CellBox grown = known_cells_box(grid, 25);
  EXPECT_EQ(grown.x0, 0);  // clipped
  EXPECT_EQ(grown.y0, 5);
  EXPECT_EQ(grown.x1, 85);
  EXPECT_EQ(grown.y1, 70);
  EXPECT_TRUE(known_cells_box(OccupancyGrid(grid.geometry()), 5).empty());
}

TEST(Crop, EveryCellKeepsItsPlaceClassAndValue) {
  const OccupancyGrid grid = sparse_grid();
  const OccupancyGrid cropped = crop(grid, known_cells_box(grid, 3));
  EXPECT_EQ(cropped.width(), 46);
  EXPECT_EQ(cropped.height(), 21);
  EXPECT_DOUBLE_EQ(cropped.geometry().origin.theta, 0.3);
  for (int iy = 0; iy < cropped.height(); ++iy) {
    for (int ix = 0; ix < cropped.width(); ++ix) {
      const Eigen::Vector2d centre = cropped.geometry().cell_center(ix, iy);
      int ox = 0, oy = 0;
      ASSERT_TRUE(grid.geometry().cell_of(centre, ox, oy));
      EXPECT_EQ(ox, ix + 17);
      EXPECT_EQ(oy, iy + 27);
      EXPECT_LT((grid.geometry().cell_center(ox, oy) - centre).norm(), 1e-9);
      EXPECT_EQ(cropped.state(ix, iy), grid.state(ox, oy));
      EXPECT_EQ(cropped.value(ix, iy), grid.value(ox, oy));
    }
  }
  EXPECT_EQ(cropped.counts().occupied, 1u);
  EXPECT_EQ(cropped.counts().free, grid.counts().free);
}

}  // namespace
}  // namespace floorgrid
