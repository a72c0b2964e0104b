// Where the laser meets walls drawn as one stroke along their middle: an analytic building whose
// outer walls are 0.5 m thick and partitions 0.12 m, drawn as one-cell lines. Without the faces'
// offsets the registration stretches the gridmap's outline onto the drawn outline and the plan
// scale comes out about the outer wall's thickness over the building's extent low.
#include "floorgrid/pipeline/wall_faces.hpp"

#include <gtest/gtest.h>

#include "floorgrid/pipeline/map_alignment.hpp"

namespace floorgrid {
namespace {

constexpr double kPlanScale = 1.25;      // world metres per plan metre
constexpr double kExterior = 0.50;       // world metres, outer walls' thickness
constexpr double kPartition = 0.12;      // world metres, partitions' thickness
constexpr double kResolution = 0.05;     // both grids, metres per cell
const Eigen::Vector2d kShift{1.3, 0.7};  // world metres: where the plan's origin lies

// A wall's centre line in plan metres, with the gaps (doors) left open along it.
struct Line {
  Eigen::Vector2d a, b;
};

// The building: a 20 x 12 plan-metre outline, three partitions with doorways.
std::vector<Line> walls(bool exterior) {
  if (exterior)
    return {{{0, 0}, {20, 0}}, {{20, 0}, {20, 12}}, {{20, 12}, {0, 12}}, {{0, 12}, {0, 0}}};
  return {{{7, 0}, {7, 5}}, {{7, 6.2}, {7, 12}}, {{13, 0}, {13, 7}}, {{13, 8.2}, {13, 12}},
          {{0, 6}, {3, 6}}, {{4.2, 6}, {7, 6}},  {{13, 4}, {16, 4}}, {{17.2, 4}, {20, 4}}};
}

void draw(OccupancyGrid& grid, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
          CellState state) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(length / (0.25 * kResolution)));
  for (int i = 0; i <= steps; ++i) {
    int ix = 0, iy = 0;
    if (grid.geometry().cell_of(a + (b - a) * (double(i) / steps), ix, iy))
      grid.set_state(ix, iy, state);
  }
}

OccupancyGrid plan_grid() {
  // Lines through cell centres: each stroke one cell, its surfaces half a cell off the line.
  GridGeometry g{
      .width = 480, .height = 320, .resolution = kResolution, .origin = {-2.025, -2.025, 0}};
  OccupancyGrid plan(g, CellState::free);
  for (bool exterior : {true, false}) {
    for (const Line& l : walls(exterior))
      draw(plan, l.a, l.b, CellState::occupied);
  }
  return plan;
}

// The world the laser sees: every wall a solid of its thickness centred on its drawn line; the
// gridmap marks the faces a robot inside sees, free space inside, unknown elsewhere.
OccupancyGrid gridmap(double partition) {
  // The outer faces through cell centres.
  GridGeometry g{
      .width = 600, .height = 400, .resolution = kResolution, .origin = {-1.025, -1.025, 0}};
  OccupancyGrid grid(g, CellState::unknown);
  const auto world = [](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    return kPlanScale * p + kShift;
  };
  const double inner = kExterior / 2;
  const Eigen::Vector2d lo = world({0, 0}) + Eigen::Vector2d(inner, inner);
  const Eigen::Vector2d hi = world({20, 12}) - Eigen::Vector2d(inner, inner);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      if ((c.array() > lo.array()).all() && (c.array() < hi.array()).all())
        grid.set_state(ix, iy, CellState::free);
    }
  }
  draw(grid, lo, {hi.x(), lo.y()}, CellState::occupied);
  draw(grid, {hi.x(), lo.y()}, hi, CellState::occupied);
  draw(grid, hi, {lo.x(), hi.y()}, CellState::occupied);
  draw(grid, {lo.x(), hi.y()}, lo, CellState::occupied);
  for (const Line& l : walls(false)) {
    const Eigen::Vector2d a = world(l.a), b = world(l.b);
    const Eigen::Vector2d along = (b - a).normalized();
    const Eigen::Vector2d across(-along.y(), along.x());
    // Clipped to the rooms: a partition starts at the outer walls' inner faces.
    const auto clip = [&](Eigen::Vector2d p) {
      return Eigen::Vector2d(std::clamp(p.x(), lo.x(), hi.x()), std::clamp(p.y(), lo.y(), hi.y()));
    };
    for (double off = -partition / 2 + 0.01; off < partition / 2; off += 0.02)
      draw(grid, clip(a + off * across), clip(b + off * across), CellState::unknown);
    for (double side : {-1.0, 1.0}) {
      draw(grid, clip(a + side * partition / 2 * across), clip(b + side * partition / 2 * across),
           CellState::occupied);
    }
  }
  return grid;
}

MapAlignment align(bool faces, double partition = kPartition) {
  MapAlignmentOptions o;
  o.faces.enabled = faces;
  return align_maps(gridmap(partition), plan_grid(), PlanWalls::raster_strokes, {}, o);
}

double plan_scale(const MapAlignment& a) {
  return 1.0 / a.registration.best.transform.scale;
}

// The fit alone, on matches made analytically: each face point of the world matched to the
// surface of the line it was drawn as (the one-cell stroke's surface on the point's side).
TEST(WallFaces, TheFitFindsTheScaleAndBothOffsetsFromAStretchedStart) {
  const double half_cell = 0.5 * kResolution;  // plan metres: a stroke's surface off its line
  struct Face {
    Eigen::Vector2d grid;    // world metres
    Eigen::Vector2d line_a;  // plan metres, the drawn line's ends
    Eigen::Vector2d line_b;
    Eigen::Vector2d normal;  // plan frame, towards the side it was seen from
    bool exterior;
  };
  std::vector<Face> faces;
  const auto world = [](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    return kPlanScale * p + kShift;
  };
  for (bool exterior : {true, false}) {
    for (const Line& l : walls(exterior)) {
      const Eigen::Vector2d along = (l.b - l.a).normalized();
      const Eigen::Vector2d left(-along.y(), along.x());
      const double thickness = exterior ? kExterior : kPartition;
      for (double side : {-1.0, 1.0}) {
        const Eigen::Vector2d normal = side * left;
        // The outline's lines run anticlockwise: the rooms lie on their left.
        if (exterior && side < 0)
          continue;
        for (double t = 0.5; t < (l.b - l.a).norm() - 0.5; t += 0.25) {
          const Eigen::Vector2d on_line = l.a + t * along;
          faces.push_back({world(on_line) + thickness / 2 * normal, l.a, l.b, normal, exterior});
        }
      }
    }
  }
  const FaceMatcher match = [&](const MapSimilarity& s, double radius) {
    std::vector<FaceObservation> out;
    for (const Face& f : faces) {
      const Eigen::Vector2d p = s.apply(f.grid);
      const Eigen::Vector2d along = (f.line_b - f.line_a).normalized();
      const Eigen::Vector2d foot = f.line_a + (p - f.line_a).dot(along) * along;
      const Eigen::Vector2d surface = foot + half_cell * f.normal;
      if (std::abs(f.normal.dot(p - surface)) <= radius)
        out.push_back({f.grid, surface, f.normal, f.exterior});
    }
    return out;
  };
  // The registration's kind of start: the outline stretched onto the drawn one, 2% low.
  MapSimilarity start;
  start.scale = 1.0 / (0.98 * kPlanScale);
  start.translation = -kShift * start.scale;
  WallFaceOptions on;
  on.enabled = true;
  const WallFaceFit fit = fit_wall_faces(match, start, on);
  ASSERT_TRUE(fit.fitted) << fit.note;
  EXPECT_NEAR(1.0 / fit.similarity.scale / kPlanScale, 1.0, 0.001) << fit.note;
  EXPECT_NEAR(fit.similarity.theta, 0.0, 1e-3);
  const double plan_per_world = fit.similarity.scale;
  EXPECT_NEAR(fit.exterior_offset / plan_per_world, kExterior / 2 - half_cell * kPlanScale, 0.01);
  EXPECT_NEAR(fit.partition_offset / plan_per_world, kPartition / 2 - half_cell * kPlanScale, 0.01);
  // Off, the start is kept.
  WallFaceOptions off;
  off.enabled = false;
  EXPECT_FALSE(fit_wall_faces(match, start, off).fitted);
}

// End to end through align_maps. Partitions 0.36 m thick here: a gridmap wall point's direction
// comes from the occupied cells within 0.25 m, so the two faces of a thinner partition read as
// one blob and tell no wall (as in real gridmaps); these keep one face per side.
TEST(WallFaces, TheMapsAlignmentFindsTheFacesAndTheScale) {
  constexpr double kThick = 0.36;
  const MapAlignment a = align(true, kThick);
  ASSERT_TRUE(a.registration.found);
  ASSERT_TRUE(a.faces.fitted) << a.faces.note;
  EXPECT_NEAR(plan_scale(a) / kPlanScale, 1.0, 0.002) << a.faces.note;
  const double plan_per_world = a.registration.best.transform.scale;
  const double half_cell = 0.5 * kResolution * kPlanScale;  // world metres
  EXPECT_NEAR(a.faces.exterior_offset / plan_per_world, kExterior / 2 - half_cell, 0.03);
  EXPECT_NEAR(a.faces.partition_offset / plan_per_world, kThick / 2 - half_cell, 0.03);
  // The maps' pairs put each gridmap face point where the truth puts it on the plan.
  std::vector<double> errors;
  for (Eigen::Index i = 0; i < a.pairs.size(); ++i) {
    const Eigen::Vector2d truth = (a.pairs.points_in_grid.col(i) - kShift) / kPlanScale;
    errors.push_back((a.pairs.points_in_plan.col(i) - truth).norm() * kPlanScale);
  }
  ASSERT_GT(errors.size(), 100u);
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.04);
  // Without the faces, the same maps come out stretched.
  EXPECT_LT(plan_scale(align(false, kThick)) / kPlanScale - 1.0, -0.008);
}

TEST(WallFaces, ThePlanAtTheFacesGrowsEachStrokeByItsOffsetIntoTheRooms) {
  const OccupancyGrid plan = plan_grid();
  const ExteriorWalls exterior(plan, 1.0);
  WallFaceFit fit;
  fit.fitted = true;
  fit.exterior_offset = 0.16;  // plan metres off the strokes' surfaces (0.025 off their lines)
  fit.partition_offset = 0.048;
  const OccupancyGrid grown = plan_at_faces(plan, exterior, fit, 0.5);
  const auto occupied = [&](double x, double y) {
    int ix = 0, iy = 0;
    return grown.geometry().cell_of({x, y}, ix, iy) && grown.state(ix, iy) == CellState::occupied;
  };
  EXPECT_TRUE(occupied(5, 0.15));  // the bottom outer wall, grown to 0.185
  EXPECT_FALSE(occupied(5, 0.25));
  EXPECT_FALSE(occupied(5, -0.15));  // never into the outside
  EXPECT_TRUE(occupied(7.06, 3));    // a partition, grown to 7.073 on either side
  EXPECT_TRUE(occupied(6.94, 3));
  EXPECT_FALSE(occupied(7.12, 3));
  EXPECT_FALSE(occupied(6.88, 3));
  // Not fitted: the plan as drawn.
  fit.fitted = false;
  EXPECT_EQ(plan_at_faces(plan, exterior, fit, 0.5).counts().occupied, plan.counts().occupied);
}

TEST(WallFaces, TheOutsideIsToldFromTheInsideThroughADoorway) {
  OccupancyGrid plan = plan_grid();
  // An entrance 1.5 plan metres wide in the bottom wall: sealed, the rooms stay inside.
  draw(plan, {9, 0}, {10.5, 0}, CellState::free);
  const ExteriorWalls exterior(plan, 1.0);
  // The bottom wall's inner surface, normal into the room: outside behind it.
  EXPECT_TRUE(exterior.exterior({5, 0.025}, {0, 1}, 0.5));
  // A partition's surface, normal into a room: a room behind it.
  EXPECT_FALSE(exterior.exterior({7.025, 3}, {1, 0}, 0.5));
  // The outer wall seen from outside: the room behind it is not outside.
  EXPECT_FALSE(exterior.exterior({5, -0.025}, {0, -1}, 0.5));
}

}  // namespace
}  // namespace floorgrid
