// rasterize(): occupied cells checked against distances computed here analytically (not with
// rasterize's own distance functions). Cells whose centre lies within 1e-9 of the wall band's
// edge are ambiguous under rounding and left out.

#include "floorgrid/maps/rasterize.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <queue>
#include <tuple>

#include "floorgrid/core/error.hpp"

namespace floorgrid {
namespace {

constexpr double kAmbiguous = 1e-9;

/// Distance from `p` to the outline of the axis-aligned rectangle [lo, hi].
double distance_to_rectangle_outline(const Eigen::Vector2d& p, const Eigen::Vector2d& lo,
                                     const Eigen::Vector2d& hi) {
  const bool inside = p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
  if (inside) {
    return std::min({p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y()});
  }
  const Eigen::Vector2d clamped = p.cwiseMax(lo).cwiseMin(hi);
  return (p - clamped).norm();
}

/// Checks every cell: occupied exactly when `distance(centre) <= reach`.
template <typename Distance>
void expect_band(const OccupancyGrid& grid, double reach, const Distance& distance,
                 std::size_t& occupied) {
  occupied = 0;
  std::size_t wrong = 0;
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      const double d = distance(grid.geometry().cell_center(ix, iy));
      if (std::abs(d - reach) < kAmbiguous) {
        continue;
      }
      const bool expected = d < reach;
      if (grid.is_occupied(ix, iy)) {
        ++occupied;
      }
      if (grid.is_occupied(ix, iy) != expected && ++wrong <= 5) {
        ADD_FAILURE() << "cell " << ix << "," << iy << " at distance " << d << " (reach " << reach
                      << ") is " << (expected ? "free" : "occupied");
      }
    }
  }
  EXPECT_EQ(wrong, 0u);
}

using RoomCase = std::tuple<double, double>;  // resolution, wall thickness

class RasterizeRoom : public ::testing::TestWithParam<RoomCase> {};

TEST_P(RasterizeRoom, SquareRoomOccupiesExactlyTheWallBand) {
  const auto [resolution, thickness] = GetParam();
  const Eigen::Vector2d lo(0.013, -0.021), hi(4.013, 3.979);  // a 4 m square, off the cell grid
  VectorFloorplan plan;
  plan.add_segment(lo, {hi.x(), lo.y()}, "W");
  plan.add_segment({hi.x(), lo.y()}, hi, "W");
  plan.add_segment(hi, {lo.x(), hi.y()}, "W");
  plan.add_segment({lo.x(), hi.y()}, lo, "W");
  RasterizeOptions options;
  options.resolution = resolution;
  options.wall_thickness = thickness;
  options.margin = 0.5;
  // The automatic grid covers the bounds plus the margin, from their lower corner.
  const OccupancyGrid automatic = rasterize(plan, options);
  EXPECT_NEAR(automatic.geometry().origin.x, lo.x() - 0.5, 1e-12);
  EXPECT_NEAR(automatic.geometry().origin.y, lo.y() - 0.5, 1e-12);
  EXPECT_EQ(automatic.width(), static_cast<int>(std::ceil(5.0 / resolution - 1e-9)));
  // That grid puts the walls a whole number of half cells from the centres (every band cell a
  // tie), so the band is checked on a grid laid off the walls' alignment.
  GridGeometry offset;
  offset.resolution = resolution;
  offset.width = offset.height = static_cast<int>(std::ceil(5.0 / resolution));
  offset.origin = {lo.x() - 0.5 + 0.37 * resolution, lo.y() - 0.5 + 0.71 * resolution, 0.0};
  const OccupancyGrid grid = rasterize(plan, options, offset);
  const double reach = 0.5 * std::max(thickness, resolution);
  std::size_t occupied = 0;
  expect_band(
      grid, reach,
      [&](const Eigen::Vector2d& p) { return distance_to_rectangle_outline(p, lo, hi); }, occupied);
  // About perimeter x band width cells.
  const double expected_cells = 16.0 * 2.0 * reach / (resolution * resolution);
  EXPECT_NEAR(static_cast<double>(occupied), expected_cells, 0.1 * expected_cells);
  EXPECT_EQ(grid.counts().unknown, 0u);  // a plan is known everywhere
}

INSTANTIATE_TEST_SUITE_P(TwoResolutionsTwoThicknesses, RasterizeRoom,
                         ::testing::Values(RoomCase{0.05, 0.10}, RoomCase{0.05, 0.30},
                                           RoomCase{0.10, 0.10}, RoomCase{0.10, 0.30}));

/// Whether the occupied cells connect `from` to `to` through 8-neighbours.
bool connected(const OccupancyGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to) {
  std::vector<bool> seen(grid.geometry().size(), false);
  std::queue<Eigen::Vector2i> queue;
  queue.push(from);
  seen[grid.index(from.x(), from.y())] = true;
  while (!queue.empty()) {
    const Eigen::Vector2i c = queue.front();
    queue.pop();
    if (c == to) {
      return true;
    }
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const Eigen::Vector2i n = c + Eigen::Vector2i(dx, dy);
        if (!grid.is_occupied(n.x(), n.y()) || seen[grid.index(n.x(), n.y())]) {
          continue;
        }
        seen[grid.index(n.x(), n.y())] = true;
        queue.push(n);
      }
    }
  }
  return false;
}

/// The occupied cell whose centre is nearest `p`.
Eigen::Vector2i nearest_occupied(const OccupancyGrid& grid, const Eigen::Vector2d& p) {
  Eigen::Vector2i best(-1, -1);
  double best_distance = HUGE_VAL;
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      const double d = (grid.geometry().cell_center(ix, iy) - p).norm();
      if (grid.is_occupied(ix, iy) && d < best_distance) {
        best_distance = d;
        best = {ix, iy};
      }
    }
  }
  return best;
}

TEST(Rasterize, ThinDiagonalWallsStayConnected) {
  // Walls of zero thickness at awkward angles: the band is half a cell wide on each side, so a
  // wall must still be one 8-connected chain of cells from end to end.
  for (const double angle_deg : {1.0, 17.0, 33.3, 45.0, 61.0, 89.5, 123.0}) {
    const double angle = angle_deg * std::numbers::pi / 180.0;
    const Eigen::Vector2d a(0.0123, 0.0071);
    const Eigen::Vector2d b = a + 6.7 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    VectorFloorplan plan;
    plan.add_segment(a, b, "W");
    RasterizeOptions options;
    options.resolution = 0.05;
    options.wall_thickness = 0.0;
    const OccupancyGrid grid = rasterize(plan, options);
    // The rule (centre within half a cell) may leave the cell holding an end free when the end
    // lies in its corner, so the chain runs between the occupied cells nearest the two ends.
    const Eigen::Vector2i from = nearest_occupied(grid, a), to = nearest_occupied(grid, b);
    EXPECT_LE((grid.geometry().cell_center(from.x(), from.y()) - a).norm(), 0.05 * std::sqrt(2.0));
    EXPECT_LE((grid.geometry().cell_center(to.x(), to.y()) - b).norm(), 0.05 * std::sqrt(2.0));
    EXPECT_TRUE(connected(grid, from, to)) << angle_deg << " degrees";
    // And no thicker than asked: every occupied centre within half a cell of the line.
    const Eigen::Vector2d d = (b - a).normalized();
    for (int iy = 0; iy < grid.height(); ++iy) {
      for (int ix = 0; ix < grid.width(); ++ix) {
        if (!grid.is_occupied(ix, iy)) {
          continue;
        }
        const Eigen::Vector2d p = grid.geometry().cell_center(ix, iy) - a;
        const double along = std::clamp(p.dot(d), 0.0, (b - a).norm());
        EXPECT_LE((p - along * d).norm(), 0.025 + 1e-12);
      }
    }
  }
}

TEST(Rasterize, CircleAndQuarterArcOccupyTheirRing) {
  VectorFloorplan plan;
  const Eigen::Vector2d c(1.017, -0.503);
  plan.add_arc(c, 2.0, 0.0, 0.0, "COLUMN");  // full circle
  const Eigen::Vector2d q(7.011, 0.007);
  plan.add_arc(q, 1.5, 0.0, std::numbers::pi / 2.0, "DOOR");
  RasterizeOptions options;
  options.resolution = 0.05;
  options.wall_thickness = 0.1;
  const OccupancyGrid grid = rasterize(plan, options);
  const auto ring = [](const Eigen::Vector2d& p, const Eigen::Vector2d& centre, double r) {
    return std::abs((p - centre).norm() - r);
  };
  const auto quarter = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d v = p - q;
    if (v.x() >= 0.0 && v.y() >= 0.0) {
      return ring(p, q, 1.5);
    }
    return std::min((p - (q + Eigen::Vector2d(1.5, 0))).norm(),
                    (p - (q + Eigen::Vector2d(0, 1.5))).norm());
  };
  std::size_t occupied = 0;
  expect_band(
      grid, 0.05, [&](const Eigen::Vector2d& p) { return std::min(ring(p, c, 2.0), quarter(p)); },
      occupied);
  // Ring areas: 2 pi r (2 reach) for the circle, a quarter of it plus two end caps for the arc.
  const double cell = 0.05 * 0.05;
  const double expected = (2 * std::numbers::pi * 2.0 * 0.1 + 0.5 * std::numbers::pi * 1.5 * 0.1 +
                           std::numbers::pi * 0.05 * 0.05) /
                          cell;
  EXPECT_NEAR(static_cast<double>(occupied), expected, 0.05 * expected);
}

TEST(Rasterize, RefusesBadOptionsAndEmptyPlans) {
  VectorFloorplan plan;
  plan.add_segment({0, 0}, {1, 0}, "W");
  RasterizeOptions options;
  options.resolution = 0.0;
  try {
    rasterize(plan, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "rasterize.resolution");
  }
  EXPECT_THROW(rasterize(VectorFloorplan(), RasterizeOptions()), InputError);
}

}  // namespace
}  // namespace floorgrid
