// The wall field against analytic walls: each cell's nearest wall point and normal, on a
// grid's occupied cells and on a vector plan's exact walls.
#include "floorgrid/localization/wall_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "floorgrid/maps/rasterize.hpp"
#include "tests/support/expect_error.hpp"

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

TEST(WallField, ASurfaceOffsetMovesTheWallsFacesOffItsCells) {
  const VectorFloorplan plan = one_wall();
  const OccupancyGrid grid = grid_of(plan);
  const WallField centres(grid);
  WallField faces(grid);
  const double half = 0.5 * grid.resolution();
  faces.set_surface_offset(half);
  EXPECT_EQ(faces.surface_offset(), half);
  for (const double dy : {-0.3, 0.2}) {
    const Eigen::Vector2d p(5.0, 2.0 + dy);
    EXPECT_NEAR(faces.distance(p), centres.distance(p) - half, 1e-6);
    // The residual is measured from the face on the viewpoint's side.
    const WallPoint* w = faces.nearest(p);
    ASSERT_NE(w, nullptr);
    const Eigen::Vector2d n = w->normal.cast<double>();
    const Eigen::Vector2d viewpoint = p + 3.0 * (p - w->point.cast<double>());
    const double r = faces.surface_residual(*w, p, viewpoint);
    EXPECT_NEAR(std::abs(r), std::abs(n.dot(p - w->point.cast<double>())) - half, 1e-6);
  }
  // Inside the wall's cell the distance is 0, not negative.
  const WallPoint* w = faces.nearest({5.0, 2.0});
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(faces.distance(w->point.cast<double>()), 0.0);
  test::expect_input_error([&] { faces.set_surface_offset(2.0 * grid.resolution()); },
                           {"surface_offset"});
  test::expect_input_error([&] { faces.set_surface_offset(-0.01); }, {"surface_offset"});
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

TEST(WallField, EveryCellOfATallMapFindsItsNearestWallAcrossTheStrips) {
  // The lookup is built on strips of 256 rows: a map of several strips, sparse scattered
  // walls, and every cell checked against brute force. The transform's 5x5 mask and its
  // labels find a wall within 5% of the nearest's distance; wall points are floats.
  GridGeometry geometry;
  geometry.width = 30;
  geometry.height = 700;
  geometry.resolution = 0.05;
  OccupancyGrid grid(geometry, CellState::free);
  std::mt19937 random(7);
  std::vector<Eigen::Vector2d> walls;
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      // Sparse walls, with a stretch without any across the second strip's border (rows
      // 230-300) so that cells there find walls only beyond it.
      const bool gap = iy >= 230 && iy < 300;
      if (!gap && std::uniform_real_distribution<>(0.0, 1.0)(random) < 0.004) {
        grid.set_state(ix, iy, CellState::occupied);
        walls.push_back(geometry.cell_center(ix, iy));
      }
    }
  }
  WallFieldOptions options;
  options.max_distance = 1.0;
  const WallField field(grid, options);
  int found = 0, beyond = 0;
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      const Eigen::Vector2d c = geometry.cell_center(ix, iy);
      double truth = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& w : walls)
        truth = std::min(truth, (w - c).norm());
      const WallPoint* w = field.nearest(c);
      if (truth > 1.05 * options.max_distance) {
        EXPECT_EQ(w, nullptr) << ix << " " << iy;
        ++beyond;
      } else if (truth < 0.95 * options.max_distance) {
        ASSERT_NE(w, nullptr) << ix << " " << iy;
        EXPECT_LE((w->point.cast<double>() - c).norm(), 1.05 * truth + 1e-4) << ix << " " << iy;
        ++found;
      }
    }
  }
  EXPECT_GT(found, 10000);
  EXPECT_GT(beyond, 100);  // the gap's middle rows
}

}  // namespace
}  // namespace floorgrid
