#include "floorgrid/localization/ray_marching.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

constexpr double kPi = std::numbers::pi;

/// A random grid: occupied cells with probability `occupied`, unknown with `unknown`.
OccupancyGrid random_grid(Random& random, const GridGeometry& geometry, double occupied,
                          double unknown) {
  OccupancyGrid grid(geometry, CellState::free);
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      const double u = random.uniform();
      if (u < occupied)
        grid.set_state(ix, iy, CellState::occupied);
      else if (u < occupied + unknown)
        grid.set_state(ix, iy, CellState::unknown);
    }
  }
  return grid;
}

/// The reference: Amanatides and Woo's cell walk over the unbounded lattice from the origin's
/// cell, testing every cell (nothing outside the grid blocks). Cells along the ray; the entry
/// of the first blocking cell, or max_cells.
double cell_walk(const OccupancyGrid& grid, bool unknown_blocks, double x, double y, double dx,
                 double dy, double max_cells) {
  const auto blocks = [&](int ix, int iy) {
    if (!grid.geometry().contains(ix, iy))
      return false;
    const CellState s = grid.state(ix, iy);
    return s == CellState::occupied || (unknown_blocks && s == CellState::unknown);
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
  double next_x = dx > 0 ? (ix + 1 - x) / dx : dx < 0 ? (ix - x) / dx : kInf;
  double next_y = dy > 0 ? (iy + 1 - y) / dy : dy < 0 ? (iy - y) / dy : kInf;
  const double delta_x = dx != 0 ? 1.0 / std::abs(dx) : kInf;
  const double delta_y = dy != 0 ? 1.0 / std::abs(dy) : kInf;
  double t = 0.0;
  while (t < max_cells) {
    if (blocks(ix, iy))
      return t;
    if (next_x < next_y) {
      t = next_x;
      next_x += delta_x;
      ix += step_x;
    } else {
      t = next_y;
      next_y += delta_y;
      iy += step_y;
    }
  }
  return max_cells;
}

TEST(GridRayCaster, MatchesTheCellWalkOnRandomMaps) {
  Random random(11);
  int rays = 0, exact = 0;
  for (int map = 0; map < 40; ++map) {
    GridGeometry geometry;
    geometry.width = static_cast<int>(random.integer(1, 150));
    geometry.height = static_cast<int>(random.integer(1, 150));
    const double occupied = random.uniform(0.0, 0.25);
    const bool unknown_blocks = map % 3 == 0;
    const OccupancyGrid grid = random_grid(random, geometry, occupied, 0.1);
    const GridRayCaster caster(grid, {.unknown_is_occupied = unknown_blocks});
    for (int i = 0; i < 2000; ++i) {
      // Origins mostly inside, some outside the grid (up to 20 cells), some in blocking cells.
      const double x = random.uniform(-20.0, geometry.width + 20.0);
      const double y = random.uniform(-20.0, geometry.height + 20.0);
      const double a = random.uniform(-kPi, kPi);
      const double max_cells = random.uniform(0.5, 250.0);
      const double dx = std::cos(a), dy = std::sin(a);
      const double expected = cell_walk(grid, unknown_blocks, x, y, dx, dy, max_cells);
      const double got = caster.cast_in_cells(x, y, dx, dy, max_cells);
      ASSERT_NEAR(got, expected, 1.0) << "map " << map << " ray " << i << " from (" << x << ", "
                                      << y << ") at " << a << " max " << max_cells;
      ++rays;
      exact += std::abs(got - expected) <= 1e-6;
    }
  }
  // Within one cell is the promise; in fact the ranges agree to rounding.
  EXPECT_GE(exact, rays - rays / 1000) << exact << " of " << rays << " agree within 1e-6 cells";
}

TEST(GridRayCaster, FansMatchTheCellWalk) {
  Random random(14);
  int rays = 0, exact = 0;
  for (int map = 0; map < 30; ++map) {
    GridGeometry geometry;
    geometry.width = static_cast<int>(random.integer(1, 150));
    geometry.height = static_cast<int>(random.integer(1, 150));
    const OccupancyGrid grid = random_grid(random, geometry, random.uniform(0.0, 0.25), 0.0);
    const GridRayCaster caster(grid);
    for (int fan = 0; fan < 200; ++fan) {
      const double x = random.uniform(-20.0, geometry.width + 20.0);
      const double y = random.uniform(-20.0, geometry.height + 20.0);
      const double max_cells = random.uniform(0.5, 250.0);
      const auto count = static_cast<std::size_t>(random.integer(1, 37));
      std::vector<double> dx(count), dy(count), out(count);
      for (std::size_t k = 0; k < count; ++k) {
        // Some exactly axis-parallel rays among random ones.
        const double a = k % 7 == 3 ? kPi / 2 * random.integer(0, 3) : random.uniform(-kPi, kPi);
        dx[k] = k % 7 == 3 ? std::round(std::cos(a)) : std::cos(a);
        dy[k] = k % 7 == 3 ? std::round(std::sin(a)) : std::sin(a);
      }
      caster.cast_fan_in_cells(x, y, dx.data(), dy.data(), count, max_cells, out.data());
      for (std::size_t k = 0; k < count; ++k) {
        const double expected = cell_walk(grid, false, x, y, dx[k], dy[k], max_cells);
        ASSERT_NEAR(out[k], expected, 1.0) << "map " << map << " fan " << fan << " ray " << k;
        EXPECT_NEAR(out[k], caster.cast_in_cells(x, y, dx[k], dy[k], max_cells), 1.0);
        ++rays;
        exact += std::abs(out[k] - expected) <= 1e-6;
      }
    }
  }
  EXPECT_GE(exact, rays - rays / 1000) << exact << " of " << rays << " agree within 1e-6 cells";
}

TEST(GridRayCaster, FanEdgeCases) {
  GridGeometry geometry;
  geometry.width = 20;
  geometry.height = 20;
  OccupancyGrid grid(geometry, CellState::free);
  grid.set_state(10, 10, CellState::occupied);
  const GridRayCaster caster(grid);
  const std::vector<double> dx = {1.0, 0.0, -1.0, 0.6}, dy = {0.0, 1.0, 0.0, 0.8};
  std::vector<double> out(4);
  caster.cast_fan_in_cells(10.5, 10.5, dx.data(), dy.data(), 4, 50.0, out.data());
  EXPECT_EQ(out, std::vector<double>(4, 0.0));  // from inside the blocking cell
  caster.cast_fan_in_cells(2.5, 10.5, dx.data(), dy.data(), 4, 50.0, out.data());
  EXPECT_DOUBLE_EQ(out[0], 7.5);
  EXPECT_EQ(out[1], 50.0);
  EXPECT_EQ(out[2], 50.0);
  caster.cast_fan_in_cells(2.5, 10.5, dx.data(), dy.data(), 4, 0.0, out.data());
  EXPECT_EQ(out, std::vector<double>(4, 0.0));
  caster.cast_fan_in_cells(std::nan(""), 10.5, dx.data(), dy.data(), 4, 5.0, out.data());
  EXPECT_EQ(out, std::vector<double>(4, 5.0));
  caster.cast_fan_in_cells(2.5, 10.5, dx.data(), dy.data(), 0, 5.0, out.data());  // no rays
}

TEST(GridRayCaster, MatchesTheCellWalkInMetresOnYawedGrids) {
  Random random(12);
  for (int map = 0; map < 10; ++map) {
    GridGeometry geometry;
    geometry.width = 120;
    geometry.height = 90;
    geometry.resolution = random.uniform(0.02, 0.2);
    geometry.origin = {random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(-kPi, kPi)};
    const OccupancyGrid grid = random_grid(random, geometry, 0.05, 0.0);
    const GridRayCaster caster(grid);
    const Eigen::AlignedBox2d box = geometry.bounds();
    for (int i = 0; i < 1000; ++i) {
      const Eigen::Vector2d origin(random.uniform(box.min().x(), box.max().x()),
                                   random.uniform(box.min().y(), box.max().y()));
      const double angle = random.uniform(-kPi, kPi);
      const double max_range = random.uniform(0.1, 30.0);
      // The same ray in cells, built independently from the grid's geometry.
      const Eigen::Vector2d c = geometry.to_cell_coordinates(origin);
      const Eigen::Vector2d tip =
          geometry.to_cell_coordinates(origin + Eigen::Vector2d(std::cos(angle), std::sin(angle)));
      const Eigen::Vector2d d = (tip - c).normalized();
      const double max_cells = max_range / geometry.resolution;
      const double walked = cell_walk(grid, false, c.x(), c.y(), d.x(), d.y(), max_cells);
      const double expected = walked >= max_cells ? max_range : walked * geometry.resolution;
      EXPECT_NEAR(caster.cast(origin, angle, max_range), expected, geometry.resolution);
    }
  }
}

TEST(GridRayCaster, AxisParallelRaysAlongCellBoundaries) {
  GridGeometry geometry;
  geometry.width = 50;
  geometry.height = 40;
  OccupancyGrid grid(geometry, CellState::free);
  for (int iy = 0; iy < 40; ++iy)
    grid.set_state(30, iy, CellState::occupied);  // a wall from x = 30 to 31
  for (int ix = 0; ix < 50; ++ix)
    grid.set_state(ix, 5, CellState::occupied);  // a wall from y = 5 to 6
  const GridRayCaster caster(grid);
  // Along +x on a cell boundary (y = 20 exactly) and inside a row.
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(10.0, 20.0, 1.0, 0.0, 100.0), 20.0);
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(10.5, 20.5, 1.0, 0.0, 100.0), 19.5);
  // Along -x: the wall at x = 30..31 is entered at x = 31.
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(45.0, 20.0, -1.0, 0.0, 100.0), 14.0);
  // Along -y onto the wall y = 5..6, entered at y = 6; along +y nothing until the edge.
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(12.0, 30.0, 0.0, -1.0, 100.0), 24.0);
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(12.0, 30.0, 0.0, 1.0, 100.0), 100.0);
  // Exactly along the wall's face x = 30 (the cells right of it are the wall).
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(30.0, 20.0, 0.0, 1.0, 100.0), 0.0);
  // Limited by the maximum range.
  EXPECT_DOUBLE_EQ(caster.cast_in_cells(10.0, 20.0, 1.0, 0.0, 19.0), 19.0);
}

TEST(GridRayCaster, EdgeCases) {
  GridGeometry geometry;
  geometry.width = 20;
  geometry.height = 20;
  geometry.resolution = 0.1;
  OccupancyGrid grid(geometry, CellState::free);
  grid.set_state(10, 10, CellState::occupied);
  const GridRayCaster caster(grid);
  // A ray starting in a blocking cell has range 0; non-positive max range gives 0.
  EXPECT_EQ(caster.cast({1.05, 1.05}, 0.3, 5.0), 0.0);
  EXPECT_EQ(caster.cast({0.5, 1.05}, 0.0, 0.0), 0.0);
  EXPECT_EQ(caster.cast({0.5, 1.05}, 0.0, -1.0), 0.0);
  // Non-finite origin: the max range.
  EXPECT_EQ(caster.cast({std::nan(""), 1.0}, 0.0, 5.0), 5.0);
  // From outside the grid, into it and onto the cell: enters at x = 1.0.
  EXPECT_NEAR(caster.cast({-3.0, 1.05}, 0.0, 10.0), 4.0, 1e-12);
  // From outside, missing the grid altogether; and from outside pointing away.
  EXPECT_EQ(caster.cast({-3.0, 5.0}, 0.0, 10.0), 10.0);
  EXPECT_EQ(caster.cast({-3.0, 1.05}, kPi, 10.0), 10.0);
  // A grid without obstacles, and an empty caster.
  const GridRayCaster open(OccupancyGrid(geometry, CellState::free));
  EXPECT_EQ(open.cast({1.0, 1.0}, 0.7, 50.0), 50.0);
  EXPECT_EQ(GridRayCaster().cast({1.0, 1.0}, 0.7, 50.0), 50.0);
}

TEST(GridRayCaster, LargeOpenMapsCapTheClearance) {
  // Clearances beyond 253 cells are stored as 253: rays still reach far obstacles exactly.
  GridGeometry geometry;
  geometry.width = 700;
  geometry.height = 600;
  OccupancyGrid grid(geometry, CellState::free);
  for (int iy = 0; iy < 5; ++iy) {
    for (int ix = 690; ix < 700; ++ix)
      grid.set_state(ix, iy, CellState::occupied);
  }
  const GridRayCaster caster(grid);
  EXPECT_EQ(caster.clearance(0, 599), 253);
  EXPECT_EQ(caster.clearance(400, 100), 253);
  EXPECT_EQ(caster.clearance(688, 2), 1);
  EXPECT_EQ(caster.clearance(689, 2), 0);
  Random random(15);
  for (int i = 0; i < 2000; ++i) {
    const double x = random.uniform(0.0, 700.0), y = random.uniform(0.0, 600.0);
    // Aim at a random point of the obstacle block, or anywhere.
    const double a =
        i % 2 == 0 ? std::atan2(random.uniform(0.0, 5.0) - y, random.uniform(690.0, 700.0) - x)
                   : random.uniform(-kPi, kPi);
    const double expected = cell_walk(grid, false, x, y, std::cos(a), std::sin(a), 2000.0);
    EXPECT_NEAR(caster.cast_in_cells(x, y, std::cos(a), std::sin(a), 2000.0), expected, 1e-6);
  }
}

TEST(GridRayCaster, UnknownCellsAreFreeUnlessAsked) {
  GridGeometry geometry;
  geometry.width = 40;
  geometry.height = 10;
  OccupancyGrid grid(geometry, CellState::free);
  for (int iy = 0; iy < 10; ++iy) {
    grid.set_state(10, iy, CellState::unknown);
    grid.set_state(30, iy, CellState::occupied);
  }
  EXPECT_DOUBLE_EQ(GridRayCaster(grid).cast_in_cells(2.0, 5.5, 1.0, 0.0, 100.0), 28.0);
  EXPECT_DOUBLE_EQ(
      GridRayCaster(grid, {.unknown_is_occupied = true}).cast_in_cells(2.0, 5.5, 1.0, 0.0, 100.0),
      8.0);
}

TEST(GridRayCaster, ClearanceIsALowerBoundOnTheDistanceToBlockingCells) {
  Random random(13);
  GridGeometry geometry;
  geometry.width = 40;
  geometry.height = 30;
  const OccupancyGrid grid = random_grid(random, geometry, 0.03, 0.0);
  const GridRayCaster caster(grid);
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      const int c = caster.clearance(ix, iy);
      if (grid.state(ix, iy) == CellState::occupied) {
        EXPECT_EQ(c, -1);
        continue;
      }
      // Smallest distance between the closed squares of this cell and of any occupied cell.
      double nearest = std::numeric_limits<double>::infinity();
      for (int oy = 0; oy < geometry.height; ++oy) {
        for (int ox = 0; ox < geometry.width; ++ox) {
          if (grid.state(ox, oy) != CellState::occupied)
            continue;
          const double gx = std::max(0, std::abs(ox - ix) - 1);
          const double gy = std::max(0, std::abs(oy - iy) - 1);
          nearest = std::min(nearest, std::hypot(gx, gy));
        }
      }
      // Exactly the distance rounded down (a lower bound that wastes under a cell).
      EXPECT_EQ(c, static_cast<int>(std::floor(nearest + 1e-12))) << "cell " << ix << ", " << iy;
    }
  }
}

}  // namespace
}  // namespace floorgrid
