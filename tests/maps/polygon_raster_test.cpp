// Zone polygons: cell-centre rasterization by the even-odd rule (holes, a rotated grid, clipping),
// disks of margin, and the ring checks (closed, simple).
#include "floorgrid/maps/polygon_raster.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/maps/plan_layers.hpp"

namespace floorgrid {
namespace {

Eigen::Matrix2Xd ring(std::initializer_list<Eigen::Vector2d> points) {
  Eigen::Matrix2Xd m(2, static_cast<Eigen::Index>(points.size()));
  Eigen::Index i = 0;
  for (const Eigen::Vector2d& p : points)
    m.col(i++) = p;
  return m;
}

GridGeometry grid(double yaw = 0.0) {
  GridGeometry g;
  g.width = 40;
  g.height = 30;
  g.resolution = 0.1;
  g.origin = {-1.0, -1.0, yaw};
  return g;
}

TEST(PolygonRaster, ASquareWithAHoleCoversTheCellsWhoseCentresItHolds) {
  // [0, 2) x [0, 1.5) minus [0.5, 1) x [0.5, 1): centres at -0.95 + 0.1 k.
  const CellMask mask = rasterize_rings({ring({{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.5}, {0.0, 1.5}}),
                                         ring({{0.5, 0.5}, {0.5, 1.0}, {1.0, 1.0}, {1.0, 0.5}})},
                                        grid());
  EXPECT_EQ(mask.count(), 20u * 15u - 5u * 5u);
  for (int iy = 0; iy < 30; ++iy) {
    for (int ix = 0; ix < 40; ++ix) {
      const Eigen::Vector2d c = grid().cell_center(ix, iy);
      const bool outer = c.x() > 0 && c.x() < 2 && c.y() > 0 && c.y() < 1.5;
      const bool hole = c.x() > 0.5 && c.x() < 1 && c.y() > 0.5 && c.y() < 1;
      ASSERT_EQ(mask.at(ix, iy), outer && !hole) << ix << ", " << iy;
    }
  }
}

TEST(PolygonRaster, FollowsARotatedGridAndClipsToIt) {
  const GridGeometry g = grid(0.3);
  const Eigen::Matrix2Xd triangle = ring({{-3.0, -3.0}, {1.5, 0.2}, {0.1, 2.2}});
  const CellMask mask = rasterize_rings({triangle}, g);
  std::size_t expected = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      bool in = true;  // left of each edge of the counter-clockwise triangle
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d a = triangle.col(k), b = triangle.col((k + 1) % 3);
        in = in && (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() > 0;
      }
      expected += in;
      ASSERT_EQ(mask.at(ix, iy), in) << ix << ", " << iy;
    }
  }
  EXPECT_GT(expected, 100u);
}

TEST(PolygonRaster, DisksMarkTheCellsWithinTheirRadius) {
  CellMask mask(grid());
  const std::size_t added =
      stamp_disks(mask, ring({{0.0, 0.0}, {5.0, 5.0}}), Eigen::Vector2d(0.32, 0.5));
  // Centres within 0.32 m of (0, 0): (0.05 + 0.1 i)^2 + (0.05 + 0.1 j)^2 <= 0.1024.
  std::size_t expected = 0;
  for (int i = -5; i < 5; ++i)
    for (int j = -5; j < 5; ++j)
      expected += std::pow(0.05 + 0.1 * i, 2) + std::pow(0.05 + 0.1 * j, 2) <= 0.1024;
  EXPECT_EQ(added, expected);
  EXPECT_EQ(mask.count(), expected);
}

TEST(PlanLayers, RingChecksFindCrossingsAndTouchesButNotNeighbours) {
  Zone square;
  square.outer = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NO_THROW(validate_zone(square, "z"));
  Zone touch = square;  // a vertex on a non-adjacent edge
  touch.outer = {{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}};
  EXPECT_TRUE(find_crossing({touch.outer}));
  Zone fold = square;  // back along the previous edge
  fold.outer = {{0, 0}, {2, 0}, {1, 0}, {1, 1}};
  EXPECT_TRUE(find_crossing({fold.outer}));
  Zone two = square;
  two.outer = {{0, 0}, {1, 0}, {0, 0}};
  try {
    validate_zone(two, "z.geojson");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs at least 3 distinct vertices (got 2)"),
              std::string::npos)
        << e.what();
  }
  Zone bad_speed = square;
  bad_speed.speed.percent = 150;
  EXPECT_THROW(validate_zone(bad_speed, "z"), InputError);
}

}  // namespace
}  // namespace floorgrid
