// Datasets from a drawing (simulate --from-plan), checked on a drawing made here whose strokes,
// doors and rooms are exact: the world's wall faces, its doors and rooms, the gridmap against
// the world through the exact warp, the truth against the drawing, determinism, drawing errors
// and bad drawings.
#include "floorgrid/simulation/plan_dataset.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "floorgrid/maps/rasterize.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

using Eigen::Vector2d;

constexpr double kPixel = 0.025;  // the drawing's resolution, the world raster's too
constexpr double kPartition = 0.15;
constexpr double kExterior = 0.35;

// A drawn line: its ends (pixel centres, metres) and whether it is an outer wall.
struct Line {
  Vector2d a, b;
  bool exterior = false;
};

// The centre of pixel k along an axis.
double at(int k) {
  return (k + 0.5) * kPixel;
}

// Three rooms in a 12 x 8 m outline drawn one pixel wide on white paper: a partition at
// x = 8 m with a 0.9 m door at y = 8 m, and one at y = 6 m in the left half with a 0.9 m door
// at x = 5 m. Door gaps are cut out of the lines.
std::vector<Line> lines() {
  const double x0 = at(80), x1 = at(560), y0 = at(80), y1 = at(400), xm = at(320), ym = at(240);
  return {{{x0, y0}, {x1, y0}, true}, {{x1, y0}, {x1, y1}, true},  {{x1, y1}, {x0, y1}, true},
          {{x0, y1}, {x0, y0}, true}, {{xm, y0}, {xm, y1}, false}, {{x0, ym}, {xm, ym}, false}};
}

bool in_door(const Vector2d& p) {
  return (std::abs(p.x() - at(320)) < 1e-9 && std::abs(p.y() - 8.0) < 0.45) ||
         (std::abs(p.y() - at(240)) < 1e-9 && std::abs(p.x() - 5.0) < 0.45);
}

OccupancyGrid drawing_raster() {
  GridGeometry g;
  g.width = 640;
  g.height = 480;
  g.resolution = kPixel;
  OccupancyGrid grid(g, CellState::free);
  for (const Line& line : lines()) {
    const int steps = static_cast<int>(std::lround((line.b - line.a).norm() / kPixel));
    for (int k = 0; k <= steps; ++k) {
      const Vector2d p = line.a + (line.b - line.a) * (double(k) / steps);
      int ix = 0, iy = 0;
      if (!in_door(p) && g.cell_of(p, ix, iy))
        grid.set_state(ix, iy, CellState::occupied);
    }
  }
  return grid;
}

PlanDrawing drawing() {
  PlanDrawing d;
  d.raster = drawing_raster();
  return d;
}

PlanWorldOptions fixed_walls() {
  PlanWorldOptions o;
  o.partition_thickness = {kPartition, kPartition};
  o.exterior_thickness = {kExterior, kExterior};
  return o;
}

Vector2d left_of_line(const Line& line) {
  const Vector2d u = (line.b - line.a).normalized();
  return {-u.y(), u.x()};
}

double distance_to_line(const Vector2d& p, const Line& line) {
  Segment s;
  s.a = line.a;
  s.b = line.b;
  return distance_to_segment(p, s);
}

TEST(PlanWorld, WallFacesLieHalfAThicknessFromTheStrokeCentres) {
  Random random(5);
  const PlanWorld world = build_plan_world(drawing(), 1.0, fixed_walls(), false, 0.3, random);
  int partition_faces = 0, exterior_faces = 0;
  for (const Segment& face : world.walls) {
    if (face.length() < 0.3)
      continue;  // corners, jambs and the glass's ends
    // The face's distance to the drawn lines it runs along.
    const Vector2d mid = (face.a + face.b) / 2;
    double best = std::numeric_limits<double>::infinity();
    bool exterior = false;
    for (const Line& line : lines()) {
      const Vector2d u = (line.b - line.a).normalized();
      if (std::abs(u.dot((face.b - face.a).normalized())) < 0.99)
        continue;
      const double d = distance_to_line(mid, line);
      if (d < best) {
        best = d;
        exterior = line.exterior;
      }
    }
    const double half = (exterior ? kExterior : kPartition) / 2;
    EXPECT_NEAR(best, half, kPixel)
        << "face from (" << face.a.transpose() << ") to (" << face.b.transpose() << ")";
    ++(exterior ? exterior_faces : partition_faces);
  }
  EXPECT_GE(exterior_faces, 4);   // the outline's inner faces (its outer faces too)
  EXPECT_GE(partition_faces, 4);  // both sides of both partitions
}

TEST(PlanWorld, FindsTheRoomsAndTheirDoors) {
  Random random(5);
  PlanWorldOptions o = fixed_walls();
  o.leaf_probability = 1.0;
  const PlanWorld world = build_plan_world(drawing(), 1.0, o, false, 0.3, random);
  ASSERT_EQ(world.regions.size(), 3u);
  std::vector<double> areas;
  for (const WorldRegion& r : world.regions)
    areas.push_back(r.area);
  std::sort(areas.begin(), areas.end());
  // 6 x 4, 6 x 4 and 6 x 8 m between the stroke centres, less half a wall all round.
  EXPECT_NEAR(areas[0], (6.0 - 0.25) * (4.0 - 0.25), 1.0);
  EXPECT_NEAR(areas[2], (6.0 - 0.25) * (8.0 - 0.35), 1.5);
  // The two doors between rooms, as wide as drawn (walls end square at a door).
  int doorways = 0;
  for (const WorldDoor& door : world.doors) {
    if (door.region_b < 0)
      continue;
    ++doorways;
    EXPECT_NEAR(door.width(), 0.9, 2 * kPixel);
    const Vector2d centre = (door.jamb_a + door.jamb_b) / 2;
    const bool lower = (centre - Vector2d(5.0, at(240))).norm() < 0.1;
    EXPECT_TRUE(lower || (centre - Vector2d(at(320), 8.0)).norm() < 0.1) << centre.transpose();
    // The lower left room, behind the only door that cuts off one room alone, is shut away:
    // a region never visited. The other door is open.
    EXPECT_EQ(door.state, lower ? "closed" : "open");
  }
  EXPECT_EQ(doorways, 2);
  EXPECT_GT(world.count(SurfaceKind::furniture), 5u);
}

// The distance from `p` to the nearest segment.
double nearest(const std::vector<Segment>& segments, const Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments)
    best = std::min(best, distance_to_segment(p, s));
  return best;
}

PlanDatasetOptions options(std::uint64_t seed) {
  PlanDatasetOptions o;
  o.seed = seed;
  o.plan_scale = 1.25;
  o.bend = 0.3;
  o.rotation_deg = 30.0;
  o.world = fixed_walls();
  return o;
}

TEST(PlanDataset, GridmapWallsLieOnTheWorldsSurfacesThroughTheWarp) {
  const PlanDataset d = simulate_from_plan(drawing(), options(3));
  const SimulatedWarp warp(d.warp);
  const std::vector<Segment> surfaces = d.world.world_segments();
  std::vector<double> off;
  const GridGeometry& g = d.gridmap.geometry();
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (d.gridmap.state(ix, iy) != CellState::occupied)
        continue;
      const InverseResult world = warp.grid_to_world(g.cell_center(ix, iy));
      ASSERT_TRUE(world.converged);
      off.push_back(nearest(surfaces, world.point));
    }
  }
  ASSERT_GT(off.size(), 300u);
  std::sort(off.begin(), off.end());
  // A cell's centre is at most half a diagonal (3.5 cm) from the surface that filled it, give or
  // take the range noise (2 cm): within a cell.
  EXPECT_LT(off[off.size() / 2], 0.025);
  EXPECT_LT(off[off.size() * 9 / 10], 0.05);
  // The run saw clutter and doors, and the statistics add up.
  EXPECT_GT(d.statistics.clutter_fraction, 0.05);
  EXPECT_EQ(d.statistics.scans, d.log.scans.size());
  EXPECT_GT(d.statistics.scans, 100u);
  EXPECT_FALSE(d.tour.visited.empty());
}

// The distance from `point_in_grid` to the nearest occupied cell within `reach` cells.
double nearest_occupied(const OccupancyGrid& grid, const Vector2d& point_in_grid, int reach) {
  const GridGeometry& g = grid.geometry();
  const Vector2d c = g.to_cell_coordinates(point_in_grid);
  double best = std::numeric_limits<double>::infinity();
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const int ix = static_cast<int>(std::floor(c.x())) + dx;
      const int iy = static_cast<int>(std::floor(c.y())) + dy;
      if (grid.is_occupied(ix, iy))
        best = std::min(best, (g.cell_center(ix, iy) - point_in_grid).norm());
    }
  }
  return best;
}

TEST(PlanDataset, TruthTakesTheDrawnCentreLinesOntoTheGridmapsWalls) {
  const PlanDataset d = simulate_from_plan(drawing(), options(3));
  const PlanTruth truth = d.truth();
  const SimulatedWarp warp(d.warp);
  EXPECT_DOUBLE_EQ(truth.plan_scale(), 1.0 / 1.25);
  int checked = 0, near_wall = 0;
  for (const Line& line : lines()) {
    const double half = (line.exterior ? kExterior : kPartition) / 2;
    const Vector2d n = left_of_line(line);
    const int steps = static_cast<int>((line.b - line.a).norm() / 0.1);
    for (int k = 0; k <= steps; ++k) {
      // A raster drawing is the world at its own resolution; the plan is the world / 1.25.
      const Vector2d world = line.a + (line.b - line.a) * (double(k) / steps);
      if (in_door(world))
        continue;
      // Only where the laser saw one of the wall's faces (not behind a cabinet or a shut door).
      if (nearest_occupied(d.gridmap, warp.world_to_grid(world + n * half), 1) > 0.05 &&
          nearest_occupied(d.gridmap, warp.world_to_grid(world - n * half), 1) > 0.05)
        continue;
      ++checked;
      // Half the wall (the face the laser saw) plus a cell's half diagonal and the noise.
      const double off = nearest_occupied(d.gridmap, truth.plan_to_grid(world / 1.25), 8);
      near_wall += off <= half + 0.035 + 0.04;
    }
  }
  ASSERT_GT(checked, 100);
  EXPECT_GE(near_wall, 0.95 * checked) << near_wall << " of " << checked;
}

TEST(PlanDataset, SameSeedSameDatasetOtherSeedAnother) {
  const PlanDataset a = simulate_from_plan(drawing(), options(11));
  const PlanDataset b = simulate_from_plan(drawing(), options(11));
  const PlanDataset c = simulate_from_plan(drawing(), options(12));
  ASSERT_EQ(a.log.scans.size(), b.log.scans.size());
  for (std::size_t i = 0; i < a.log.scans.size(); ++i)
    ASSERT_EQ(a.log.scans[i].ranges, b.log.scans[i].ranges) << "scan " << i;
  EXPECT_EQ(a.gridmap.states(), b.gridmap.states());
  EXPECT_EQ(a.manual_pairs.points_in_grid, b.manual_pairs.points_in_grid);
  EXPECT_NE(a.gridmap.states(), c.gridmap.states());
  EXPECT_NE(a.world.objects.size() + a.log.scans.size(), 0u);
}

TEST(PlanDataset, DrawingErrorsChangeTheWorldInAFewPlaces) {
  PlanDatasetOptions o = options(4);
  const PlanDataset as_drawn = simulate_from_plan(drawing(), o);
  o.drawing_errors = true;
  const PlanDataset wrong = simulate_from_plan(drawing(), o);
  EXPECT_TRUE(as_drawn.world.errors.empty());
  ASSERT_GE(wrong.world.errors.size(), 2u);
  for (const DrawingError& e : wrong.world.errors) {
    if (e.kind == "partition_moved") {
      EXPECT_GE(std::abs(e.amount), o.world.partition_shift.min);
      EXPECT_LE(std::abs(e.amount), o.world.partition_shift.max);
    } else if (e.kind == "door_shifted") {
      EXPECT_GE(std::abs(e.amount), o.world.door_shift.min);
      EXPECT_LE(std::abs(e.amount), o.world.door_shift.max);
    } else {
      EXPECT_TRUE(e.kind == "partition_added" || e.kind == "partition_removed") << e.kind;
    }
  }
  // The drawing, and so the truth's reference, is the same; the world's walls are not.
  EXPECT_EQ(as_drawn.world.drawn_ink, wrong.world.drawn_ink);
  EXPECT_NE(as_drawn.world.walls.size(), wrong.world.walls.size());
}

TEST(PlanDataset, DefaultScaleKeepsAVectorDrawingsDoorsWalkable) {
  // The same rooms as vector walls at 0.6 of their size: doors 0.54 m wide at scale 1.
  PlanDrawing small;
  const std::vector<Line> all = lines();
  for (const Line& line : all) {
    const Vector2d u = (line.b - line.a).normalized();
    Vector2d from = line.a;
    const double length = (line.b - line.a).norm();
    for (double s = 0.0; s <= length; s += kPixel) {
      const Vector2d p = line.a + u * s;
      const bool gap = in_door(p);
      if (gap && (p - from).norm() > kPixel) {
        small.vector.add_segment(from * 0.6, (p - u * kPixel) * 0.6, "WALLS");
        from = p;
      }
      if (gap)
        from = p + u * kPixel;
    }
    small.vector.add_segment(from * 0.6, line.b * 0.6, "WALLS");
  }
  PlanDatasetOptions o;
  o.seed = 2;
  const PlanDataset d = simulate_from_plan(small, o);
  // A doorway of 0.8 m needs a scale of about 0.8 / 0.54 (the doors measured a little narrower
  // on the coarse raster that scale is found on).
  EXPECT_GT(d.statistics.plan_scale_low, 0.8 / 0.54 - 0.05);
  EXPECT_LT(d.statistics.plan_scale_low, 0.8 / 0.54 + 0.25);
  EXPECT_GE(d.statistics.plan_scale, d.statistics.plan_scale_low);
  EXPECT_LE(d.statistics.plan_scale, 2.0);
}

TEST(PlanDataset, RefusesDrawingsWithoutWallsOrInside) {
  GridGeometry g;
  g.width = 200;
  g.height = 200;
  g.resolution = 0.05;
  PlanDrawing blank;
  blank.raster = OccupancyGrid(g, CellState::free);
  test::expect_input_error([&] { simulate_from_plan(blank, {}); }, {"plan", "no walls"});
  PlanDrawing line = blank;
  for (int ix = 20; ix < 180; ++ix)
    line.raster->set_state(ix, 100, CellState::occupied);
  test::expect_input_error([&] { simulate_from_plan(line, {}); }, {"plan", "no inside"});
  test::expect_input_error([&] { simulate_from_plan(PlanDrawing{}, {}); }, {"plan", "no walls"});
  PlanDatasetOptions bad;
  bad.plan_scale = -1.0;
  test::expect_input_error([&] { simulate_from_plan(drawing(), bad); }, {"plan_scale"});
}

}  // namespace
}  // namespace floorgrid
