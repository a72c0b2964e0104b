// Semi-real datasets from a corrected log: checked on a log of a known room, whose walls and size
// are exact, so the drawn plan, the truth and the pairs can be held against them.
#include "floorgrid/simulation/log_dataset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
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

// A 12 m x 7 m room (inner faces at x = 0.013 and 12.013, y = 0.021 and 7.021, inside cells,
// not on their borders) with a 4 m partition from the top wall at x = 6.013, and a 0.3 m box
// (clutter) on the floor.
std::vector<Segment> room() {
  return {segment(0.013, 0.021, 12.013, 0.021), segment(12.013, 0.021, 12.013, 7.021),
          segment(12.013, 7.021, 0.013, 7.021), segment(0.013, 7.021, 0.013, 0.021),
          segment(6.013, 7.021, 6.013, 3.0),    segment(3.0, 1.5, 3.3, 1.5),
          segment(3.3, 1.5, 3.3, 1.8),          segment(3.3, 1.8, 3.0, 1.8),
          segment(3.0, 1.8, 3.0, 1.5)};
}

// The room with a fence across its lower left: posts 4 cm square every 15 cm from x = 3 to 5 m
// at y = 4.2 m, a wall the laser sees as dots with free cells between them.
std::vector<Segment> room_with_fence() {
  std::vector<Segment> walls = room();
  for (double x = 3.0; x <= 5.0 + 1e-9; x += 0.15) {
    walls.push_back(segment(x, 4.18, x + 0.04, 4.18));
    walls.push_back(segment(x + 0.04, 4.18, x + 0.04, 4.22));
    walls.push_back(segment(x + 0.04, 4.22, x, 4.22));
    walls.push_back(segment(x, 4.22, x, 4.18));
  }
  return walls;
}

// A corrected log of a loop through the room: a scan every 0.5 m and 20 degrees, as sparse as
// the Radish logs, the poses exact.
RobotLog room_log(const std::vector<Segment>& walls = room()) {
  const SegmentRayCaster caster(walls);
  LaserSpec spec;
  spec.range_noise_sigma = 0.005;
  spec.random_reading_fraction = 0.0;
  Random random(3);
  RobotLog log;
  const Vector2d corners[] = {{1.5, 2.5}, {10.5, 1.2}, {10.5, 5.8}, {8.0, 5.8}, {1.5, 5.8}};
  double time = 1.0;
  for (int lap = 0; lap < 2; ++lap) {
    for (std::size_t c = 0; c < 5; ++c) {
      const Vector2d a = corners[c], b = corners[(c + 1) % 5];
      const int steps = static_cast<int>(std::ceil((b - a).norm() / 0.5));
      for (int i = 0; i < steps; ++i) {
        const Vector2d p = a + (b - a) * (double(i) / steps);
        const double heading = std::atan2((b - a).y(), (b - a).x()) + 0.35 * std::sin(i + lap);
        const Pose2 pose{p.x(), p.y(), heading};
        const SimulatedScan scan = simulate_scan(caster, pose, spec, random);
        log.scans.push_back(to_laser_scan(scan, pose.compose(spec.laser_in_robot), pose, time));
        time += 1.0;
      }
    }
  }
  return log;
}

const RobotLog& shared_log() {
  static const RobotLog log = room_log();
  return log;
}

LogDatasetOptions fixed(double plan_scale, double rotation_deg, double bend) {
  LogDatasetOptions o;
  o.plan_scale = plan_scale;
  o.rotation_deg = rotation_deg;
  o.bend = bend;
  o.wall_thickness_px = 3;
  return o;
}

// Distance from each plan wall pixel, mapped by the truth, to the nearest gridmap wall: the
// drawing lies on the walls the laser found (up to its stroke behind them).
TEST(LogDataset, PlanWallsMapOntoTheGridmapWallsThroughTheTruth) {
  for (const double rotation : {0.0, 37.0, -140.0}) {
    const LogDataset d = simulate_from_log(shared_log(), fixed(1.6, rotation, 0.4));
    const PlanTruth truth = d.truth();
    const DistanceField walls = occupied_distance_field(d.gridmap, 5.0);
    const GridGeometry& plan = d.plan_raster.geometry();
    std::size_t pixels = 0, near = 0;
    for (int iy = 0; iy < plan.height; ++iy) {
      for (int ix = 0; ix < plan.width; ++ix) {
        if (d.plan_raster.state(ix, iy) != CellState::occupied)
          continue;
        ++pixels;
        near += walls.at(truth.plan_to_grid(plan.cell_center(ix, iy))) <= 0.2;
      }
    }
    ASSERT_GT(pixels, 500u) << rotation;
    EXPECT_GT(double(near) / double(pixels), 0.97) << rotation;
    EXPECT_NEAR(d.statistics.rotation_deg, rotation, 1e-12);
  }
}

// The room's inner width on the drawing, in the plan's units through the plan's scale, is the
// true 12 m to less than a pixel: wall surfaces stay where the laser found them, on the centres
// of the cells its beams ended in (the stroke grows behind them; drawn from the cells' edges
// instead, the room would be a cell narrower, 11.95 m, or two, as here with faces on cell edges).
TEST(LogDataset, RasterWallSurfacesKeepTheRoomsSize) {
  for (const double plan_scale : {0.5, 1.0, 2.0}) {
    const LogDataset d = simulate_from_log(shared_log(), fixed(plan_scale, 0.0, 0.0));
    EXPECT_DOUBLE_EQ(d.plan_per_world, 1.0 / plan_scale);
    const GridGeometry& plan = d.plan_raster.geometry();
    EXPECT_NEAR(plan.resolution, 0.05 / plan_scale, 1e-12);
    // Along the row through y = 1.0 (world), below the partition and away from the box.
    const Vector2d probe =
        d.truth().world_to_plan(SimulatedWarp(d.warp).grid_to_world({6.0, 1.0}).point);
    const int iy = static_cast<int>(plan.to_cell_coordinates(probe).y());
    const int mid = static_cast<int>(plan.to_cell_coordinates(probe).x());
    int left = mid, right = mid;
    while (left > 0 && d.plan_raster.state(left, iy) != CellState::occupied)
      --left;
    while (right < plan.width - 1 && d.plan_raster.state(right, iy) != CellState::occupied)
      ++right;
    const double inner_width_world = (right - left - 1) * plan.resolution / d.plan_per_world;
    EXPECT_NEAR(inner_width_world, 12.0, 0.03) << "plan scale " << plan_scale;
  }
}

TEST(LogDataset, ClutterIsLeftOutOfThePlan) {
  const LogDataset d = simulate_from_log(shared_log(), fixed(1.0, 0.0, 0.0));
  EXPECT_GT(d.statistics.clutter_cells, 0u);
  // The box at (3.0-3.3, 1.5-1.8) is in the gridmap but not on the plan.
  const SimulatedWarp warp(d.warp);
  const Vector2d box = d.truth().world_to_plan(warp.grid_to_world({3.15, 1.5}).point);
  int ix = 0, iy = 0;
  ASSERT_TRUE(d.plan_raster.geometry().cell_of(box, ix, iy));
  for (int dy = -4; dy <= 4; ++dy) {
    for (int dx = -4; dx <= 4; ++dx)
      EXPECT_FALSE(d.plan_raster.is_occupied(ix + dx, iy + dy));
  }
}

// A wall seen as dots is drawn as a wall: the fence's posts are a few cells apart with free
// cells between (a closing does not join the dots of a one-cell line), yet one blob 2 m long.
TEST(LogDataset, AWallSeenAsDotsIsDrawn) {
  const LogDataset d = simulate_from_log(room_log(room_with_fence()), fixed(1.0, 0.0, 0.0));
  const SimulatedWarp warp(d.warp);
  const GridGeometry& plan = d.plan_raster.geometry();
  const auto drawn_near = [&](const Vector2d& in_grid) {
    const Vector2d p = d.truth().world_to_plan(warp.grid_to_world(in_grid).point);
    int ix = 0, iy = 0;
    if (!plan.cell_of(p, ix, iy))
      return false;
    for (int dy = -2; dy <= 2; ++dy) {
      for (int dx = -2; dx <= 2; ++dx) {
        if (d.plan_raster.is_occupied(ix + dx, iy + dy))
          return true;
      }
    }
    return false;
  };
  int drawn = 0, probes = 0;
  for (double x = 3.1; x <= 4.9; x += 0.1, ++probes)
    drawn += drawn_near({x, 4.2});
  EXPECT_GE(drawn, probes - 1) << drawn << " of " << probes;
  // The box is still clutter.
  EXPECT_FALSE(drawn_near({3.15, 1.65}));
}

TEST(LogDataset, ManualPairsAndStartFollowTheTruth) {
  const LogDataset d = simulate_from_log(shared_log(), fixed(1.3, 75.0, 0.5));
  ASSERT_GE(d.manual_pairs.size(), 3);  // a plain room has few corners
  const PlanTruth truth = d.truth();
  for (Eigen::Index i = 0; i < d.manual_pairs.size(); ++i) {
    EXPECT_LT((truth.plan_to_grid(d.manual_pairs.points_in_plan.col(i)) -
               d.manual_pairs.points_in_grid.col(i))
                  .norm(),
              0.3);
  }
  const Pose2 start = truth.pose_plan_to_grid(d.start_in_plan);
  EXPECT_NEAR(start.x, d.start_in_grid.x, 1e-6);
  EXPECT_NEAR(start.y, d.start_in_grid.y, 1e-6);
  EXPECT_NEAR(normalize_angle(start.theta - d.start_in_grid.theta), 0.0, 1e-6);
  EXPECT_NEAR(std::abs(d.statistics.bend_deviation), 0.5, 1e-9);
}

// The warp's best global similarity: without a bend the warp is one (scale 1); a bend stretches
// the walls on one side of its axis and shrinks them on the other, so the best similarity's
// scale moves from 1, but by less than the largest strain.
TEST(LogDataset, TheWarpsBestSimilarityScaleStaysWithinItsStrain) {
  EXPECT_NEAR(simulate_from_log(shared_log(), fixed(1.3, 20.0, 0.0)).statistics.warp_fit_scale, 1.0,
              1e-12);
  const LogDataset bent = simulate_from_log(shared_log(), fixed(1.3, 20.0, 1.0));
  ASSERT_GT(bent.statistics.max_bend_strain, 0.01);
  EXPECT_NE(bent.statistics.warp_fit_scale, 1.0);
  EXPECT_LT(std::abs(bent.statistics.warp_fit_scale - 1.0), bent.statistics.max_bend_strain);
}

TEST(LogDataset, VectorPlanTracesTheSameWalls) {
  LogDatasetOptions o = fixed(0.8, 20.0, 0.3);
  o.vector_plan = true;
  const LogDataset d = simulate_from_log(shared_log(), o);
  ASSERT_GT(d.plan_vector.segments().size(), 8u);
  const PlanTruth truth = d.truth();
  const DistanceField walls = occupied_distance_field(d.gridmap, 5.0);
  std::size_t near = 0;
  for (const Segment& s : d.plan_vector.segments())
    near += walls.at(truth.plan_to_grid(0.5 * (s.a + s.b))) <= 0.25;
  EXPECT_GT(double(near) / double(d.plan_vector.segments().size()), 0.95);
}

TEST(LogDataset, SameSeedSameDatasetAndChoicesDrawnInRange) {
  LogDatasetOptions o;
  o.seed = 11;
  const LogDataset a = simulate_from_log(shared_log(), o);
  const LogDataset b = simulate_from_log(shared_log(), o);
  EXPECT_EQ(a.plan_raster.states(), b.plan_raster.states());
  EXPECT_EQ(a.gridmap.states(), b.gridmap.states());
  EXPECT_EQ(*a.options.plan_scale, *b.options.plan_scale);
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    o.seed = seed;
    const LogDataset d = simulate_from_log(shared_log(), o);
    EXPECT_GE(*d.options.plan_scale, 0.5);
    EXPECT_LE(*d.options.plan_scale, 2.0);
    EXPECT_GE(*d.options.bend, 0.2);
    EXPECT_LE(*d.options.bend, 1.0);
    EXPECT_GE(*d.options.wall_thickness_px, 2);
    EXPECT_LE(*d.options.wall_thickness_px, 4);
  }
}

TEST(LogDataset, ALogWithoutTimestampsGetsThemInLineOrder) {
  RobotLog log = shared_log();
  for (LaserScan& scan : log.scans)
    scan.timestamp = 0.0;
  const LogDataset d = simulate_from_log(log, fixed(1.0, 0.0, 0.0));
  for (std::size_t i = 0; i < d.log.scans.size(); ++i)
    EXPECT_EQ(d.log.scans[i].timestamp, double(i + 1));
}

TEST(LogDataset, BadOptionsAndEmptyLogsAreRefusedNamingTheField) {
  LogDatasetOptions o;
  o.plan_scale = -1.0;
  test::expect_input_error([&] { simulate_from_log(shared_log(), o); }, {"plan_scale"});
  o = {};
  o.bend = std::nan("");
  test::expect_input_error([&] { simulate_from_log(shared_log(), o); }, {"bend"});
  o = {};
  o.rotation_deg = INFINITY;
  test::expect_input_error([&] { simulate_from_log(shared_log(), o); }, {"rotation"});
  test::expect_input_error([&] { simulate_from_log(RobotLog{}, LogDatasetOptions{}); }, {"log"});
}

}  // namespace
}  // namespace floorgrid
