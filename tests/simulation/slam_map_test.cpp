#include "floorgrid/simulation/slam_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/maps/rasterize.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

using Eigen::Vector2d;

Segment segment(double ax, double ay, double bx, double by) {
  Segment s;
  s.a = {ax, ay};
  s.b = {bx, by};
  return s;
}

// The room's walls lie inside cell columns and rows (not on cell boundaries, which are at
// multiples of 0.05 m): x = 0.013 and 6.013, y = 0.021 and 4.021.
constexpr double kX0 = 0.013, kX1 = 6.013, kY0 = 0.021, kY1 = 4.021;

std::vector<Segment> room_walls() {
  return {segment(kX0, kY0, kX1, kY0), segment(kX1, kY0, kX1, kY1), segment(kX1, kY1, kX0, kY1),
          segment(kX0, kY1, kX0, kY0)};
}

/// Scans of the room from five places, each facing four ways, so every wall is seen head-on.
std::vector<SlamMapInput> scan_room(const LaserSpec& spec, std::uint64_t seed) {
  const SegmentRayCaster caster(room_walls());
  Random random(seed);
  std::vector<SlamMapInput> scans;
  const Vector2d places[] = {{1.5, 1.2}, {3.0, 2.0}, {4.5, 2.8}, {1.2, 3.0}, {4.8, 1.0}};
  for (const Vector2d& p : places) {
    for (int k = 0; k < 4; ++k) {
      const Pose2 robot{p.x(), p.y(), k * std::numbers::pi / 2 + 0.1};
      scans.push_back(to_slam_map_input(simulate_scan(caster, robot, spec, random)));
    }
  }
  return scans;
}

LaserSpec noiseless() {
  LaserSpec spec;
  spec.range_noise_sigma = 0.0;
  spec.random_reading_fraction = 0.0;
  return spec;
}

Vector2d identity(const Vector2d& p) {
  return p;
}

/// A rigid transform world -> grid: rotation by 0.3 rad, then a shift.
struct RigidWarp {
  Pose2 T_grid_world{5.0, -3.0, 0.3};
  Vector2d operator()(const Vector2d& p) const { return T_grid_world.transform(p); }
  Vector2d inverse(const Vector2d& g) const { return T_grid_world.inverse().transform(g); }
};

/// How far a grid cell's box reaches beyond its centre across a wall of direction `wall_in_grid`.
double half_extent_across(const Vector2d& wall_in_grid, double resolution) {
  const Vector2d n = Vector2d(-wall_in_grid.y(), wall_in_grid.x()).normalized();
  return 0.5 * resolution * (std::abs(n.x()) + std::abs(n.y()));
}

/// Distance from a cell's box (not its centre) to the nearest wall, as seen in the world: the
/// centre's distance minus the box's half extent across that wall. The box is a square of the
/// grid; `grid_to_world` is rigid, so the box keeps its shape in the world.
double box_distance_to_walls(const Vector2d& centre_in_world, double resolution,
                             double grid_yaw_in_world) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& wall : room_walls()) {
    const Vector2d dir_in_grid = rotation_2d(-grid_yaw_in_world) * (wall.b - wall.a);
    best = std::min(best, distance_to_segment(centre_in_world, wall) -
                              half_extent_across(dir_in_grid, resolution));
  }
  return best;
}

bool inside_room(const Vector2d& p) {
  return p.x() > kX0 && p.x() < kX1 && p.y() > kY0 && p.y() < kY1;
}

struct CellTally {
  int occupied_far = 0;                // occupied but more than one cell from every wall
  int wall_cells = 0;                  // cells a wall passes through
  int wall_occupied = 0;               // of those, occupied
  int wall_core = 0;                   // cells a wall crosses within a quarter cell of their centre
  int wall_core_occupied = 0;          // of those, occupied
  int inside = 0;                      // cells more than one cell inside the room
  int inside_free = 0;                 // of those, free
  int inside_occupied = 0;             // of those, occupied
  int outside = 0;                     // cells more than two cells outside the room
  int outside_unknown = 0;             // of those, unknown
  int near_outside = 0;                // cells more than two cells but at most 1 m outside the room
  int near_outside_unknown = 0;        // of those, unknown
  double max_occupied_distance = 0.0;  // box distance of the farthest occupied cell, metres
};

/// Classifies every cell of `map` against the room, mapping centres back to the world.
template <typename GridToWorld>
CellTally tally(const OccupancyGrid& map, GridToWorld grid_to_world, double grid_yaw_in_world) {
  CellTally t;
  const double res = map.resolution();
  for (int iy = 0; iy < map.height(); ++iy) {
    for (int ix = 0; ix < map.width(); ++ix) {
      const Vector2d c = grid_to_world(map.geometry().cell_center(ix, iy));
      const double d = box_distance_to_walls(c, res, grid_yaw_in_world);
      const CellState s = map.state(ix, iy);
      if (s == CellState::occupied)
        t.max_occupied_distance = std::max(t.max_occupied_distance, d);
      if (s == CellState::occupied && d > res + 1e-9)
        ++t.occupied_far;
      if (d <= 1e-9) {
        ++t.wall_cells;
        t.wall_occupied += s == CellState::occupied ? 1 : 0;
      }
      if (d <= -0.25 * res) {
        ++t.wall_core;
        t.wall_core_occupied += s == CellState::occupied ? 1 : 0;
      } else if (d > res && inside_room(c)) {
        ++t.inside;
        t.inside_free += s == CellState::free ? 1 : 0;
        t.inside_occupied += s == CellState::occupied ? 1 : 0;
      } else if (d > 2 * res) {
        ++t.outside;
        t.outside_unknown += s == CellState::unknown ? 1 : 0;
        if (d <= 1.0) {
          ++t.near_outside;
          t.near_outside_unknown += s == CellState::unknown ? 1 : 0;
        }
      }
    }
  }
  return t;
}

TEST(SlamMap, NoiselessRoomOccupiesExactlyTheWallCells) {
  const OccupancyGrid map = build_slam_map(scan_room(noiseless(), 1), identity);
  const GridGeometry& g = map.geometry();
  // Axis-aligned, origin a multiple of the resolution, covering the room plus the 1 m margin.
  EXPECT_EQ(g.origin.theta, 0.0);
  EXPECT_NEAR(g.origin.x / 0.05, std::round(g.origin.x / 0.05), 1e-9);
  EXPECT_NEAR(g.origin.y / 0.05, std::round(g.origin.y / 0.05), 1e-9);
  EXPECT_LE(g.origin.x, kX0 - 1.0);
  EXPECT_GT(g.origin.x, kX0 - 1.05);
  EXPECT_LE(g.origin.y, kY0 - 1.0);
  EXPECT_GT(g.origin.y, kY0 - 1.05);
  EXPECT_GE(g.origin.x + g.width * 0.05, kX1 + 1.0);
  EXPECT_LT(g.origin.x + g.width * 0.05, kX1 + 1.05 + 1e-9);
  EXPECT_GE(g.origin.y + g.height * 0.05, kY1 + 1.0);

  const CellTally t = tally(map, identity, 0.0);
  // The occupied cells are exactly the cells the walls pass through.
  EXPECT_LE(t.max_occupied_distance, 1e-9);
  EXPECT_EQ(t.wall_cells, 400);  // 2 x (121 + 81) cells less the 4 shared corners
  EXPECT_EQ(t.wall_occupied, t.wall_cells);
  // Free inside, unknown outside (a closed room: no beam leaves it).
  EXPECT_GT(t.inside, 9000);
  EXPECT_EQ(t.inside_free, t.inside);
  EXPECT_EQ(t.inside_occupied, 0);
  EXPECT_GT(t.outside, 3000);
  EXPECT_EQ(t.outside_unknown, t.outside);
}

TEST(SlamMap, NoisyRoomOccupiesOnlyCellsWithinOneCellOfTheWalls) {
  // The SPEC's range noise (sigma 0.02 m), first without random readings.
  LaserSpec spec;
  spec.random_reading_fraction = 0.0;
  const CellTally quiet = tally(build_slam_map(scan_room(spec, 2), identity), identity, 0.0);
  EXPECT_EQ(quiet.occupied_far, 0) << "farthest occupied cell " << quiet.max_occupied_distance;
  EXPECT_GE(quiet.wall_occupied, quiet.wall_cells * 95 / 100);
  EXPECT_EQ(quiet.inside_occupied, 0);
  EXPECT_GE(quiet.inside_free, quiet.inside * 999 / 1000);
  EXPECT_EQ(quiet.outside_unknown, quiet.outside);  // 2 cells out would take 5-sigma noise

  // With the SPEC's 1% random readings: they stop short of the wall (a laser cannot read past
  // it) and leave lone hits inside; min_hits and the ratio drop the lone hits, so occupied cells
  // stay within one cell of the walls and nothing outside is ever seen.
  const CellTally t = tally(build_slam_map(scan_room(LaserSpec{}, 2), identity), identity, 0.0);
  EXPECT_EQ(t.occupied_far, 0) << "farthest occupied cell " << t.max_occupied_distance << " m";
  EXPECT_GE(t.wall_occupied, t.wall_cells * 95 / 100);
  EXPECT_EQ(t.inside_occupied, 0);
  EXPECT_GE(t.inside_free, t.inside * 999 / 1000);
  EXPECT_EQ(t.near_outside_unknown, t.near_outside);
}

TEST(SlamMap, RigidWarpMapsOccupiedCellsBackOntoTheWalls) {
  const RigidWarp warp;
  const auto back = [&](const Vector2d& g) { return warp.inverse(g); };
  // Without noise: only cells the warped walls pass through.
  const OccupancyGrid exact = build_slam_map(scan_room(noiseless(), 3), warp);
  const CellTally te = tally(exact, back, warp.T_grid_world.theta);
  EXPECT_LE(te.max_occupied_distance, 1e-9);
  // Cells the slanted walls only clip at a corner catch few endpoints; those they cross near
  // the centre are all occupied.
  EXPECT_GE(te.wall_occupied, te.wall_cells * 85 / 100);
  EXPECT_EQ(te.wall_core_occupied, te.wall_core);
  EXPECT_GT(te.wall_core, 250);
  EXPECT_EQ(te.inside_free, te.inside);
  EXPECT_EQ(te.outside_unknown, te.outside);
  // With the SPEC's noise and random readings: within one cell.
  const OccupancyGrid noisy = build_slam_map(scan_room(LaserSpec{}, 3), warp);
  const CellTally tn = tally(noisy, back, warp.T_grid_world.theta);
  EXPECT_EQ(tn.occupied_far, 0) << "farthest occupied cell " << tn.max_occupied_distance << " m";
  EXPECT_GE(tn.wall_core_occupied, tn.wall_core * 98 / 100);
  EXPECT_EQ(tn.inside_occupied, 0);
  EXPECT_GE(tn.inside_free, tn.inside * 999 / 1000);
}

TEST(SlamMap, SameSeedSameMapBytes) {
  const RigidWarp warp;
  const OccupancyGrid a = build_slam_map(scan_room(LaserSpec{}, 11), warp);
  const OccupancyGrid b = build_slam_map(scan_room(LaserSpec{}, 11), warp);
  const OccupancyGrid c = build_slam_map(scan_room(LaserSpec{}, 12), warp);
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  EXPECT_EQ(a.geometry().origin.x, b.geometry().origin.x);
  EXPECT_EQ(a.states(), b.states());
  EXPECT_EQ(a.values(), b.values());
  EXPECT_NE(a.states(), c.states());  // the noise shows
}

/// One scan of single beams from (0.05, 0.05) along +x with the given readings.
SlamMapInput beams_along_x(std::vector<double> ranges, double max_range = 10.0) {
  SlamMapInput in;
  in.laser_pose_in_world = {0.05, 0.05, 0.0};
  in.start_angle = 0.0;
  in.angle_increment = 0.0;
  in.max_range = max_range;
  in.ranges = std::move(ranges);
  return in;
}

TEST(SlamMap, CountsFollowTheBeamRules) {
  SlamMapOptions options;
  options.resolution = 0.1;
  options.margin = 0.0;
  options.max_piece_length = 0.3;  // pieces must not count their joints twice
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A return at 1.0 m, a no-return (reaches free_range_for_no_return = 0.57 m), and four
  // readings without a usable distance.
  options.free_range_for_no_return = 0.57;
  const SlamMapCounts counts = count_slam_map(
      {beams_along_x({1.0, 10.0, nan, 0.0, -1.0, -std::numeric_limits<double>::infinity()})},
      identity, options);
  EXPECT_EQ(counts.beams_used, 2u);
  EXPECT_EQ(counts.beams_skipped, 4u);
  const GridGeometry& g = counts.geometry;
  EXPECT_EQ(g.origin.x, 0.0);
  EXPECT_EQ(g.origin.y, 0.0);
  EXPECT_EQ(g.width, 11);  // x from 0.05 to 1.05
  EXPECT_EQ(g.height, 1);
  for (int ix = 0; ix < 11; ++ix) {
    // The return: misses in cells 0..9, its hit in cell 10. The no-return, from 0.05 to 0.62:
    // misses in cells 0..6, its last cell included, and no hit.
    EXPECT_EQ(counts.hits[ix], ix == 10 ? 1u : 0u) << ix;
    EXPECT_EQ(counts.misses[ix], (ix <= 9 ? 1u : 0u) + (ix <= 6 ? 1u : 0u)) << ix;
  }
  // One piece or many: the same counts under the identity.
  SlamMapOptions one_piece = options;
  one_piece.max_piece_length = 100.0;
  const SlamMapCounts same =
      count_slam_map({beams_along_x({1.0, 10.0, nan, 0.0, -1.0, -1.0})}, identity, one_piece);
  EXPECT_EQ(same.hits, counts.hits);
  EXPECT_EQ(same.misses, counts.misses);
  // Without free_range_for_no_return, a no-return reaches the scan's max range.
  options.free_range_for_no_return.reset();
  const SlamMapCounts to_max = count_slam_map({beams_along_x({4.0}, 2.0)}, identity, options);
  EXPECT_EQ(to_max.geometry.width, 21);  // x from 0.05 to 2.05
  EXPECT_EQ(to_max.hits, std::vector<std::uint32_t>(21, 0));
}

TEST(SlamMap, ClassificationUsesMinHitsAndTheRatio) {
  SlamMapCounts counts;
  counts.geometry.width = 6;
  counts.geometry.height = 1;
  counts.geometry.resolution = 0.05;
  counts.hits = {2, 2, 1, 0, 1, 5};
  counts.misses = {6, 7, 0, 0, 1, 0};
  const OccupancyGrid map = classify_slam_map(counts, {});
  EXPECT_EQ(map.state(0, 0), CellState::occupied);  // 2 / 8 = 0.25
  EXPECT_EQ(map.state(1, 0), CellState::free);      // 2 / 9 < 0.25
  EXPECT_EQ(map.state(2, 0), CellState::unknown);   // one hit, never passed through
  EXPECT_EQ(map.state(3, 0), CellState::unknown);   // never observed
  EXPECT_EQ(map.state(4, 0), CellState::free);      // too few hits
  EXPECT_EQ(map.state(5, 0), CellState::occupied);
  EXPECT_EQ(map.value(0, 0), kOccupancyOccupied);
  EXPECT_EQ(map.value(1, 0), kOccupancyFree);
  EXPECT_EQ(map.value(3, 0), kOccupancyUnknown);
  SlamMapOptions strict;
  strict.min_hits = 3;
  EXPECT_EQ(classify_slam_map(counts, strict).state(0, 0), CellState::free);
}

TEST(SlamMap, FreeSpaceFollowsACurvedWarpPieceByPiece) {
  // A bend y_grid = y + k x^2: the 20 m beam along the world x axis becomes a parabola in the
  // grid. Joined 1 m pieces stay within k / 4 of it; one straight chord would be up to 1 m off.
  const double k = 0.01;
  const auto bend = [k](const Vector2d& p) { return Vector2d(p.x(), p.y() + k * p.x() * p.x()); };
  SlamMapInput in;
  in.laser_pose_in_world = {0.0, 0.0, 0.0};
  in.max_range = 30.0;
  in.ranges = {20.0};
  const auto worst_offset = [&](double piece) {
    SlamMapOptions options;
    options.max_piece_length = piece;
    const SlamMapCounts counts = count_slam_map({in}, bend, options);
    const GridGeometry& g = counts.geometry;
    double worst = 0.0;
    int hit_cells = 0;
    for (int iy = 0; iy < g.height; ++iy) {
      for (int ix = 0; ix < g.width; ++ix) {
        const std::size_t i = static_cast<std::size_t>(iy) * g.width + ix;
        hit_cells += counts.hits[i] > 0 ? 1 : 0;
        if (counts.hits[i] > 0) {
          int ex = 0, ey = 0;
          EXPECT_TRUE(g.cell_of(bend({20.0, 0.0}), ex, ey));
          EXPECT_EQ(ix, ex);
          EXPECT_EQ(iy, ey);
        }
        if (counts.misses[i] == 0)
          continue;
        const Vector2d c = g.cell_center(ix, iy);
        // Vertical offset of the cell centre from the parabola, less what a cell crossed by a
        // line of that slope can be off: (res / 2)(1 + |slope|).
        const double slope = 2 * k * c.x();
        worst = std::max(worst, std::abs(c.y() - k * c.x() * c.x()) -
                                    0.5 * g.resolution * (1 + std::abs(slope)));
      }
    }
    EXPECT_EQ(hit_cells, 1);
    return worst;
  };
  EXPECT_LE(worst_offset(1.0), k / 4 * 1.1 + 0.5 * 0.05 * 2 * k * 1.0);  // chord sag + slope change
  EXPECT_GT(worst_offset(100.0), 0.5);
}

TEST(SlamMap, NothingToTraceGivesAnEmptyGrid) {
  const OccupancyGrid none = build_slam_map({}, identity);
  EXPECT_EQ(none.width(), 0);
  EXPECT_EQ(none.height(), 0);
  const OccupancyGrid unusable = build_slam_map({beams_along_x({0.0, -2.0})}, identity);
  EXPECT_EQ(unusable.geometry().size(), 0u);
}

TEST(SlamMap, BadOptionsNameTheField) {
  const auto with = [](auto edit, const char* field) {
    SlamMapOptions options;
    edit(options);
    test::expect_input_error([&] { build_slam_map({beams_along_x({1.0})}, identity, options); },
                             {field});
  };
  with([](SlamMapOptions& o) { o.resolution = 0.0; }, "slam_map.resolution");
  with([](SlamMapOptions& o) { o.margin = -1.0; }, "slam_map.margin");
  with([](SlamMapOptions& o) { o.min_hits = 0; }, "slam_map.min_hits");
  with([](SlamMapOptions& o) { o.occupied_ratio = 1.5; }, "slam_map.occupied_ratio");
  with([](SlamMapOptions& o) { o.max_piece_length = 0.0; }, "slam_map.max_piece_length");
  with([](SlamMapOptions& o) { o.free_range_for_no_return = -3.0; },
       "slam_map.free_range_for_no_return");
  with([](SlamMapOptions& o) { o.max_cells = 10; }, "slam_map.max_cells");
  test::expect_input_error(
      [] {
        build_slam_map({beams_along_x({1.0})},
                       [](const Vector2d&) { return Vector2d(std::nan(""), 0.0); });
      },
      {"world_to_grid"});
}

}  // namespace
}  // namespace floorgrid
