#include "floorgrid/localization/pair_extraction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/robot/odometry_noise.hpp"

namespace floorgrid {
namespace {

/// A 10 x 6 m room (walls) in a map frame, and a scan from its centre in the world, where the
/// world is `world_per_map` times larger.
struct Room {
  OccupancyGrid grid;
  WallField walls;
  explicit Room(double size_factor = 1.0) {
    VectorFloorplan plan;
    const double w = 10.0 * size_factor, h = 6.0 * size_factor;
    plan.add_segment({0, 0}, {w, 0}, "W");
    plan.add_segment({w, 0}, {w, h}, "W");
    plan.add_segment({w, h}, {0, h}, "W");
    plan.add_segment({0, h}, {0, 0}, "W");
    RasterizeOptions o;
    o.wall_thickness = 0.0;
    grid = rasterize(plan, o);
    walls = WallField(grid);
  }
};

/// A scan at the room centre facing +x whose beams meet the walls of a 10 x 6 m room exactly,
/// except beam 5 (a chair 1 m away) and beam 7 (no return).
LaserScan centre_scan() {
  LaserScan scan;
  scan.start_angle = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 20;  // 21 beams over 180 degrees
  scan.max_range = 30.0;
  scan.robot_pose = scan.laser_pose = {5.0, 3.0, 0.0};
  for (int i = 0; i <= 20; ++i) {
    const double a = scan.angle(static_cast<std::size_t>(i));
    const double c = std::cos(a), s = std::sin(a);
    double r = 1e9;
    if (c > 1e-9)
      r = std::min(r, 5.0 / c);
    if (s > 1e-9)
      r = std::min(r, 3.0 / s);
    if (s < -1e-9)
      r = std::min(r, -3.0 / s);
    scan.ranges.push_back(static_cast<float>(r));
  }
  scan.ranges[5] = 1.0f;
  scan.ranges[7] = 30.0f;
  return scan;
}

TEST(PairExtraction, WallEndpointsBecomePairsAndTheRestIsCounted) {
  const Room plan, grid;
  const LaserScan scan = centre_scan();
  PairCollector pairs;
  PairRejections rejected;
  PairExtractionOptions options;
  options.beam_step = 1;
  options.max_pairs_per_scan = 100;
  // Plan and grid frames both put the robot at the room centre (world = map here).
  extract_scan_pairs(scan, {5.0, 3.0, 0.0}, 1.0, {5.0 + 1.0, 3.0 - 1.0, 0.0}, plan.walls,
                     Room().walls, options, pairs, rejected);
  EXPECT_EQ(rejected.no_return, 1u);
  EXPECT_EQ(rejected.off_plan_wall, 1u);  // the chair
  // The grid pose is 1 m off in x and y: every endpoint misses the grid room's walls by 1 m.
  EXPECT_EQ(rejected.off_grid_wall, 19u);
  EXPECT_EQ(pairs.size(), 0u);
  // With the right grid pose every wall endpoint is a pair.
  PairCollector good;
  PairRejections none;
  extract_scan_pairs(scan, {5.0, 3.0, 0.0}, 1.0, {5.0, 3.0, 0.0}, plan.walls, grid.walls, options,
                     good, none);
  EXPECT_EQ(good.size(), 19u);
  EXPECT_EQ(none.off_grid_wall, 0u);
}

TEST(PairExtraction, PlanEndpointsShrinkByThePlanScale) {
  // The plan is drawn 1/1.1 of the world's size: world metres per plan metre 1.1.
  const Room small(1.0 / 1.1), world;
  LaserScan scan = centre_scan();
  PairCollector pairs;
  PairRejections rejected;
  PairExtractionOptions options;
  options.beam_step = 1;
  options.max_pairs_per_scan = 100;
  extract_scan_pairs(scan, {5.0 / 1.1, 3.0 / 1.1, 0.0}, 1.1, {5.0, 3.0, 0.0}, small.walls,
                     world.walls, options, pairs, rejected);
  ASSERT_EQ(pairs.size(), 19u);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_NEAR((pairs.plan[i] * 1.1 - pairs.grid[i]).norm(), 0.0, 1e-5);
  }
  const ReferencePairs p = pairs.pairs();
  EXPECT_EQ(p.size(), 19);
  // Subsampling and the cap.
  PairCollector fewer;
  PairRejections r2;
  options.beam_step = 2;
  options.max_pairs_per_scan = 4;
  extract_scan_pairs(scan, {5.0 / 1.1, 3.0 / 1.1, 0.0}, 1.1, {5.0, 3.0, 0.0}, small.walls,
                     world.walls, options, fewer, r2);
  EXPECT_EQ(fewer.size(), 4u);
  EXPECT_EQ(r2.subsampled, 10u);
  EXPECT_EQ(r2.total() + fewer.size(), 21u);
}

TEST(OdometryNoise, KeepsTheFirstPoseAndLaserOffsetAndIsSeeded) {
  RobotLog log;
  for (int i = 0; i < 50; ++i) {
    LaserScan s;
    s.robot_pose = {0.1 * i, 0.02 * i, 0.01 * i};
    s.laser_pose = s.robot_pose.compose({0.2, 0.0, 0.0});
    s.timestamp = 1.0 + i;
    log.scans.push_back(s);
  }
  const RobotLog a = add_odometry_noise(log, {0.05, 0.01, 0.02, 0.05}, 3);
  const RobotLog b = add_odometry_noise(log, {0.05, 0.01, 0.02, 0.05}, 3);
  EXPECT_EQ(a.scans.front().robot_pose.x, 0.0);
  EXPECT_GT(
      (a.scans.back().robot_pose.translation() - log.scans.back().robot_pose.translation()).norm(),
      1e-3);
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    EXPECT_EQ(a.scans[i].robot_pose.x, b.scans[i].robot_pose.x);
    const Pose2 offset = a.scans[i].robot_pose.between(a.scans[i].laser_pose);
    EXPECT_NEAR(offset.x, 0.2, 1e-12);
    EXPECT_NEAR(offset.theta, 0.0, 1e-12);
  }
  const RobotLog none = add_odometry_noise(log, {0, 0, 0, 0}, 3);
  EXPECT_NEAR(none.scans.back().robot_pose.x, log.scans.back().robot_pose.x, 1e-12);
}

}  // namespace
}  // namespace floorgrid
