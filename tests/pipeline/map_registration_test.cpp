// The gridmap registered on the plan directly, checked against the simulator's exact warp over
// the whole scale range a plan of unknown resolution may have.
#include "floorgrid/pipeline/map_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>
#include <numbers>

#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid {
namespace {

const SimulatedDataset& office() {
  static const SimulatedDataset d = simulate("office", 2);
  return d;
}

// The office's plan drawn `factor` times too large, as a raster of a fixed number of cells per
// world metre (as a scanned drawing would be).
OccupancyGrid plan_raster(const SimulatedDataset& d, double factor) {
  RasterizeOptions options;
  options.resolution = 0.05 * factor;
  options.wall_thickness = 0.1 * factor;
  options.margin = 1.0 * factor;
  return rasterize(filter_layers(d.plan, {{"WALLS"}, {}}).scaled(factor), options);
}

// Mean distance, in world metres, between where the registration and the truth put the
// gridmap's occupied cells on the plan.
double registration_error(const MapSimilarity& t, const SimulatedDataset& d, double factor) {
  const PlanTruth truth(d.warp, d.plan_scale * factor);
  double sum = 0.0;
  int n = 0;
  const GridGeometry& g = d.gridmap.geometry();
  for (int iy = 0; iy < g.height; iy += 7) {
    for (int ix = 0; ix < g.width; ix += 7) {
      if (d.gridmap.state(ix, iy) != CellState::occupied)
        continue;
      const Eigen::Vector2d p = g.cell_center(ix, iy);
      const InverseResult exact = truth.grid_to_plan(p);
      sum += (t.apply(p) - exact.point).norm() / (d.plan_scale * factor);
      ++n;
    }
  }
  return sum / n;
}

TEST(MapRegistration, FindsScaleRotationAndPlaceOverTheWholeRange) {
  const SimulatedDataset& d = office();
  for (const double factor : {0.3, 1.0, 3.5}) {
    const MapRegistration r =
        register_maps(d.gridmap, plan_raster(d, factor), PlanWalls::vector_lines);
    ASSERT_TRUE(r.found) << factor;
    const double true_scale = d.plan_scale * factor;  // plan metres per world metre
    EXPECT_NEAR(r.best.transform.scale / true_scale, 1.0, 0.005) << factor;
    EXPECT_LT(registration_error(r.best.transform, d, factor), 0.15) << factor;
    EXPECT_GT(r.best.on_walls, 0.5) << factor;
    EXPECT_LT(r.best.in_free_space, 0.05) << factor;
    EXPECT_GT(r.best.score, r.runner_up().score + 0.1) << factor;
  }
}

TEST(MapRegistration, AnotherBuildingsPlanScoresFarBelowTheRightOne) {
  const SimulatedDataset& d = office();
  const MapRegistration right =
      register_maps(d.gridmap, plan_raster(d, 1.0), PlanWalls::vector_lines);
  const SimulatedDataset warehouse = simulate("warehouse", 1);
  RasterizeOptions options;
  const MapRegistration wrong =
      register_maps(d.gridmap, rasterize(filter_layers(warehouse.plan, {{"WALLS"}, {}}), options),
                    PlanWalls::vector_lines);
  ASSERT_TRUE(wrong.found);
  EXPECT_LT(wrong.best.score, 0.5 * right.best.score);
}

// The office's walls drawn turned by `turn` in the plan's own frame, as a DXF's lines are
// rasterized for the plan filter: one cell wide along each line.
VectorFloorplan turned_walls(const SimulatedDataset& d, double turn) {
  const VectorFloorplan walls = filter_layers(d.plan, {{"WALLS"}, {}});
  const Eigen::Rotation2Dd r(turn);
  VectorFloorplan turned;
  for (const Segment& s : walls.segments())
    turned.add_segment(r * s.a, r * s.b, walls.layers()[static_cast<std::size_t>(s.layer)]);
  for (const Arc& a : walls.arcs()) {
    turned.add_arc(r * a.center, a.radius, a.start_angle + turn, a.end_angle + turn,
                   walls.layers()[static_cast<std::size_t>(a.layer)]);
  }
  return turned;
}

TEST(MapRegistration, FindsAVectorPlanDrawnAtAnyAngle) {
  // A line drawn one cell wide a few degrees off the grid's axes is a staircase of cells whose
  // edges all run along the axes; the plan's walls must still be found at the line's angle
  // (taken as axis-aligned, the office turned 17 degrees was registered 1.35 m off).
  const SimulatedDataset& d = office();
  RasterizeOptions options;
  options.wall_thickness = 0.0;
  for (const double degrees : {8.3, 17.0, 31.0}) {
    const double turn = degrees * std::numbers::pi / 180.0;
    const MapRegistration r = register_maps(d.gridmap, rasterize(turned_walls(d, turn), options),
                                            PlanWalls::vector_lines);
    ASSERT_TRUE(r.found) << degrees;
    EXPECT_NEAR(r.best.transform.scale / d.plan_scale, 1.0, 0.005) << degrees;
    // The truth turned as the plan was: where it puts the gridmap's walls, in world metres.
    MapSimilarity truth_turn;
    truth_turn.theta = turn;
    MapSimilarity unturned = r.best.transform;
    unturned.theta -= turn;
    unturned.translation = truth_turn.inverse(r.best.transform.translation);
    EXPECT_LT(registration_error(unturned, d, 1.0), 0.15) << degrees;
    EXPECT_GT(r.best.score, r.runner_up().score + 0.1) << degrees;
  }
}

TEST(MapRegistration, MapsWithoutWallsFindNothing) {
  const SimulatedDataset& d = office();
  GridGeometry g;
  g.width = 50;
  g.height = 40;
  const OccupancyGrid empty(g, CellState::free);
  EXPECT_FALSE(register_maps(d.gridmap, empty, PlanWalls::raster_strokes).found);
  EXPECT_FALSE(register_maps(empty, plan_raster(d, 1.0), PlanWalls::vector_lines).found);
}

// Six rooms of a known building (world metres): thick outer walls, thinner inner walls with
// doors. Every face a laser sees lies on a line of the gridmap's cell centres (the gridmap's
// origin is at -1 m, its cells 0.05 m), so that the gridmap's own quantization (unbiased, but up
// to half a cell per wall) does not blur what is measured here: where the plan's strokes are.
std::vector<Eigen::AlignedBox2d> known_walls() {
  const auto box = [](double x0, double y0, double x1, double y1) {
    return Eigen::AlignedBox2d(Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1));
  };
  const double x0 = 0.025, y0 = 0.025, x1 = 23.375, y1 = 14.625, outer = 0.27, inner = 0.15;
  std::vector<Eigen::AlignedBox2d> walls = {
      box(x0 - outer, y0 - outer, x1 + outer, y0), box(x0 - outer, y1, x1 + outer, y1 + outer),
      box(x0 - outer, y0, x0, y1), box(x1, y0, x1 + outer, y1)};
  for (const double x : {7.425, 15.825}) {  // inner walls across, a door low and high
    walls.push_back(box(x, y0, x + inner, 2.17));
    walls.push_back(box(x, 3.09, x + inner, 10.52));
    walls.push_back(box(x, 11.47, x + inner, y1));
  }
  const double y = 6.925;  // the corridor's wall along, a door in every room
  for (const auto& [from, to] : {std::pair{x0, 2.61}, {3.57, 10.22}, {11.19, 18.04}, {19.0, x1}})
    walls.push_back(box(from, y, to, y + inner));
  return walls;
}

bool inside_wall(const std::vector<Eigen::AlignedBox2d>& walls, const Eigen::Vector2d& p) {
  return std::any_of(walls.begin(), walls.end(), [&](const auto& b) { return b.contains(p); });
}

// The gridmap a laser makes from inside: 0.05 m cells, free along every beam, occupied where
// beams end (on the walls' faces), seen from a lattice of places in the rooms.
OccupancyGrid laser_gridmap(const std::vector<Eigen::AlignedBox2d>& walls) {
  std::vector<Segment> faces;
  for (const auto& b : walls) {
    const Eigen::Vector2d c[4] = {
        b.corner(Eigen::AlignedBox2d::BottomLeft), b.corner(Eigen::AlignedBox2d::BottomRight),
        b.corner(Eigen::AlignedBox2d::TopRight), b.corner(Eigen::AlignedBox2d::TopLeft)};
    for (int i = 0; i < 4; ++i)
      faces.push_back({c[i], c[(i + 1) % 4], 0});
  }
  const SegmentRayCaster caster(faces);
  GridGeometry g;
  g.resolution = 0.05;
  g.origin = Pose2{-1.0, -1.0, 0.0};
  g.width = 520;
  g.height = 340;
  OccupancyGrid grid(g, CellState::unknown);
  std::vector<Eigen::Vector2d> ends;
  for (double x = 0.6; x < 23.0; x += 1.3) {
    for (double y = 0.6; y < 14.2; y += 1.1) {
      const Eigen::Vector2d from(x, y);
      if (inside_wall(walls, from))
        continue;
      for (int i = 0; i < 720; ++i) {
        const double angle = i * std::numbers::pi / 360.0;
        const auto hit = caster.cast(from, angle, 30.0);
        if (!hit)
          continue;
        const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
        int ix = 0, iy = 0;
        for (double r = 0.0; r < hit->range - 0.03; r += 0.02) {
          if (g.cell_of(from + r * direction, ix, iy))
            grid.set_state(ix, iy, CellState::free);
        }
        ends.push_back(from + hit->range * direction);
      }
    }
  }
  for (const Eigen::Vector2d& e : ends) {
    int ix = 0, iy = 0;
    if (g.cell_of(e, ix, iy))
      grid.set_state(ix, iy, CellState::occupied);
  }
  return grid;
}

// The building drawn as a raster plan: a pixel is black where its centre lies in a wall, white
// elsewhere; `t` takes world metres to plan metres.
OccupancyGrid drawn_plan(const std::vector<Eigen::AlignedBox2d>& walls, const MapSimilarity& t,
                         double resolution, const Eigen::Vector2d& pixel_shift) {
  GridGeometry g;
  g.resolution = resolution;
  const Eigen::Vector2d corner = t.apply(Eigen::Vector2d(-2.0, -2.0)) + pixel_shift * resolution;
  g.origin = Pose2{corner.x(), corner.y(), 0.0};
  g.width = static_cast<int>(28.0 * t.scale / resolution);
  g.height = static_cast<int>(19.0 * t.scale / resolution);
  OccupancyGrid plan(g, CellState::free);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (inside_wall(walls, t.inverse(g.cell_center(ix, iy))))
        plan.set_state(ix, iy, CellState::occupied);
    }
  }
  return plan;
}

TEST(MapRegistration, RasterWallsAreWhereTheirStrokesMeetTheRooms) {
  // Strokes of 3.5 and 6 pixels: their centres lie 7.5 and 13.5 cm behind the faces the laser
  // saw, which over 23 m is a scale error of up to 1%. How a drawing's pixels fall on the walls
  // moves each wall by up to half a pixel: the bias is the mean over placements of the pixels.
  const std::vector<Eigen::AlignedBox2d> walls = known_walls();
  const OccupancyGrid gridmap = laser_gridmap(walls);
  const auto scale_error = [&](double true_scale, double pixel_shift, PlanWalls kind) {
    MapSimilarity truth;
    truth.scale = true_scale;  // plan metres per world metre
    truth.translation = {3.1, -1.7};
    const OccupancyGrid plan = drawn_plan(walls, truth, 0.043 * true_scale,
                                          Eigen::Vector2d(pixel_shift, 0.7 * pixel_shift));
    const MapRegistration r = register_maps(gridmap, plan, kind);
    EXPECT_TRUE(r.found);
    EXPECT_NEAR(r.best.transform.theta, 0.0, 1e-3);
    return r.best.transform.scale / true_scale - 1.0;
  };
  const double a = scale_error(1.0 / 0.87, 0.0, PlanWalls::raster_strokes);
  const double b = scale_error(0.61, 0.5, PlanWalls::raster_strokes);
  EXPECT_LT(std::abs(a), 1e-3);
  EXPECT_LT(std::abs(b), 1e-3);
  EXPECT_LT(std::abs(0.5 * (a + b)), 5e-4) << a << " " << b;
  // The same drawing matched on its strokes' centres is off by the strokes' depth.
  EXPECT_GT(scale_error(1.0 / 0.87, 0.0, PlanWalls::vector_lines), 1.5e-3);
}

TEST(MapSimilarity, InverseUndoesApply) {
  MapSimilarity t;
  t.scale = 2.5;
  t.theta = 0.7;
  t.translation = {3.0, -4.0};
  const Eigen::Vector2d g(1.25, -7.5);
  EXPECT_LT((t.inverse(t.apply(g)) - g).norm(), 1e-12);
  const Pose2 pose = t.apply(Pose2{1.0, 2.0, 0.5});
  EXPECT_NEAR(pose.theta, 1.2, 1e-12);
}

}  // namespace
}  // namespace floorgrid
