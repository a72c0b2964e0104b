// Scan matching against analytic walls: a scan of a known room matched from a perturbed pose
// recovers the true pose; a corridor is degenerate along its axis; a scan that does not fit is
// refused.
#include "floorgrid/localization/scan_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/expect_error.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

struct Walls {
  VectorFloorplan plan;
  OccupancyGrid grid;
  WallField field;
  explicit Walls(VectorFloorplan p)
      : plan(std::move(p)), grid(test::room_grid(plan)), field(plan, grid.geometry()) {}
};

ScanObservation scan_of(const VectorFloorplan& walls, const Pose2& pose) {
  const RobotLog log = test::log_along(walls, {pose});
  return make_observation(log.scans[0], {.max_beams = 180});
}

TEST(ScanMatcher, RecoversTheTruePoseFromAPerturbedOne) {
  const Walls room(test::asymmetric_room());
  for (const Pose2& truth : {Pose2{3.0, 5.0, 0.2}, Pose2{8.0, 2.0, 2.5}, Pose2{6.0, 6.5, -1.2}}) {
    const ScanObservation scan = scan_of(room.plan, truth);
    const ScanMatch m = match_scan(room.field, scan, truth.compose({0.2, -0.15, 0.06}), 1.0);
    ASSERT_TRUE(m.ok()) << to_string(m.failure);
    EXPECT_LT((m.pose.translation() - truth.translation()).norm(), 0.015);
    EXPECT_LT(std::abs(normalize_angle(m.pose.theta - truth.theta)), 0.005);
    EXPECT_GT(m.inliers, m.endpoints / 2);
  }
}

TEST(ScanMatcher, ACorridorIsDegenerateAlongItsAxis) {
  // Two long parallel walls 2 m apart: nothing fixes the position along them.
  VectorFloorplan corridor;
  corridor.add_segment({-50.0, 0.0}, {50.0, 0.0}, "W");
  corridor.add_segment({-50.0, 2.0}, {50.0, 2.0}, "W");
  const Walls walls(corridor);
  const Pose2 truth{0.0, 1.0, 0.0};
  const ScanMatch m =
      match_scan(walls.field, scan_of(walls.plan, truth), truth.compose({0.1, 0.1, 0.0}), 1.0);
  EXPECT_EQ(m.failure, ScanMatchFailure::degenerate);
  EXPECT_NEAR(std::abs(m.weak_direction.x()), 1.0, 1e-3);
  // Across the corridor the match still found the truth.
  EXPECT_NEAR(m.pose.y, truth.y, 0.02);
}

TEST(ScanMatcher, AScanThatDoesNotFitIsRefused) {
  const Walls room(test::asymmetric_room());
  const Pose2 truth{3.0, 5.0, 0.2};
  // A scan of another place (a round hall of radius 3 m): too few endpoints find a wall.
  VectorFloorplan hall;
  for (int k = 0; k < 36; ++k) {
    const double a = k * M_PI / 18, b = (k + 1) * M_PI / 18;
    hall.add_segment({3.0 + 3.0 * std::cos(a), 5.0 + 3.0 * std::sin(a)},
                     {3.0 + 3.0 * std::cos(b), 5.0 + 3.0 * std::sin(b)}, "W");
  }
  const ScanMatch other = match_scan(room.field, scan_of(hall, truth), truth, 1.0);
  EXPECT_EQ(other.failure, ScanMatchFailure::too_few_inliers);
  // A correction larger than max_correction is refused even when the match converges.
  ScanMatchOptions strict;
  strict.max_correction = 0.05;
  const ScanMatch limited = match_scan(room.field, scan_of(room.plan, truth),
                                       truth.compose({0.2, 0.0, 0.0}), 1.0, strict);
  EXPECT_FALSE(limited.ok());
}

// A room drawn in ink as a raster plan: 0.3 m thick walls whose cells lie wholly outside the
// room's 10 x 8 m inside, so the ink's edges are the faces the laser meets.
OccupancyGrid inked_room() {
  GridGeometry g;
  g.resolution = 0.1;
  g.width = 120;
  g.height = 100;
  g.origin = {-1.0, -1.0, 0.0};
  OccupancyGrid ink(g, CellState::free);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      const bool inside = c.x() > 0.0 && c.x() < 10.0 && c.y() > 0.0 && c.y() < 8.0;
      const bool near = c.x() > -0.3 && c.x() < 10.3 && c.y() > -0.3 && c.y() < 8.3;
      if (near && !inside)
        ink.set_cell(ix, iy, CellState::occupied, kOccupancyOccupied);
    }
  }
  return ink;
}

TEST(ScanMatcher, MeetsARasterPlansWallsAtTheInksEdge) {
  VectorFloorplan room;
  room.add_segment({0, 0}, {10, 0}, "W");
  room.add_segment({10, 0}, {10, 8}, "W");
  room.add_segment({10, 8}, {0, 8}, "W");
  room.add_segment({0, 8}, {0, 0}, "W");
  const OccupancyGrid ink = inked_room();
  WallField centres(ink);
  WallField edges(ink);
  edges.set_surface_offset(0.5 * ink.geometry().resolution);
  // Facing the far wall with a 180-degree laser: matched onto the cells' centres, every wall
  // ahead lies half a cell (5 cm) deeper than the laser saw it, and the match stops short of
  // the truth by about that; matched onto the ink's edges it finds the truth.
  for (const Pose2& truth : {Pose2{6.0, 4.0, 0.0}, Pose2{4.0, 3.0, 2.0}}) {
    const ScanObservation scan = scan_of(room, truth);
    const Pose2 start = truth.compose({0.1, 0.05, 0.02});
    const ScanMatch on_edges = match_scan(edges, scan, start, 1.0);
    ASSERT_TRUE(on_edges.ok()) << to_string(on_edges.failure);
    EXPECT_LT((on_edges.pose.translation() - truth.translation()).norm(), 0.015);
    const ScanMatch on_centres = match_scan(centres, scan, start, 1.0);
    const Eigen::Vector2d ahead(std::cos(truth.theta), std::sin(truth.theta));
    EXPECT_GT(ahead.dot(on_centres.pose.translation() - truth.translation()), 0.03);
  }
}

// A drawn room (10 x 8 m with a pillar, single lines) built with walls whose faces lie
// `shift` plan metres in front of the lines, at `scale` world metres per plan metre.
VectorFloorplan room_with_faces(double shift, double scale) {
  VectorFloorplan room;
  const auto box = [&](double x0, double y0, double x1, double y1) {
    room.add_segment({x0 * scale, y0 * scale}, {x1 * scale, y0 * scale}, "W");
    room.add_segment({x1 * scale, y0 * scale}, {x1 * scale, y1 * scale}, "W");
    room.add_segment({x1 * scale, y1 * scale}, {x0 * scale, y1 * scale}, "W");
    room.add_segment({x0 * scale, y1 * scale}, {x0 * scale, y0 * scale}, "W");
  };
  box(shift, shift, 10.0 - shift, 8.0 - shift);             // the room's inside faces
  box(6.0 - shift, 5.0 - shift, 7.5 + shift, 5.8 + shift);  // the pillar's outside faces
  return room;
}

TEST(ScaleFit, TellsASurfaceShiftFromTheScale) {
  constexpr double kScale = 1.3, kShift = 0.05;  // world m per plan m; plan m
  const Walls drawn(room_with_faces(0.0, 1.0));
  const VectorFloorplan built = room_with_faces(kShift, kScale);
  std::vector<Pose2> truth_in_plan, starts;
  for (int i = 0; i < 24; ++i) {
    const double x = 1.5 + 7.0 * ((i * 7) % 24) / 24.0, y = 1.2 + 2.5 * ((i * 5) % 12) / 12.0;
    truth_in_plan.push_back({x, y, 0.7 * i});
    starts.push_back(truth_in_plan.back().compose({0.04, -0.03, 0.01}));
  }
  std::vector<Pose2> truth_in_world;
  for (const Pose2& p : truth_in_plan)
    truth_in_world.push_back({p.x * kScale, p.y * kScale, p.theta});
  const RobotLog log = test::log_along(built, truth_in_world);
  std::vector<ScanObservation> scans;
  for (const LaserScan& scan : log.scans)
    scans.push_back(make_observation(scan, {.max_beams = 180}));
  std::vector<const ScanObservation*> views;
  for (const ScanObservation& scan : scans)
    views.push_back(&scan);
  // The scale alone: every room looks smaller than drawn by two faces' shifts, so the scale
  // comes out low by about that share (1.1% here).
  const ScaleFit alone = fit_scale(drawn.field, views, starts, kScale * 1.005);
  EXPECT_LT(alone.scale / kScale - 1.0, -0.005);
  EXPECT_EQ(alone.surface_shift, 0.0);
  // Fitted with the shift: both found, and the poses with them.
  const ScaleFit both = fit_scale(drawn.field, views, starts, kScale * 1.005, {}, 30, 6, true);
  EXPECT_NEAR(both.scale / kScale, 1.0, 0.002);
  EXPECT_NEAR(both.surface_shift, kShift, 0.01);
  EXPECT_GT(both.surface_shift_std, 0.0);
  EXPECT_LT(both.surface_shift_std, 0.01);
  for (std::size_t i = 0; i < truth_in_plan.size(); ++i)
    EXPECT_LT((both.poses[i].translation() - truth_in_plan[i].translation()).norm(), 0.02) << i;
}

TEST(ScanMatcher, RefusesBadOptions) {
  ScanMatchOptions options;
  options.min_correspondence = 1.0;  // above max_correspondence
  test::expect_input_error([&] { validate(options); }, {"min_correspondence"});
}

}  // namespace
}  // namespace floorgrid
