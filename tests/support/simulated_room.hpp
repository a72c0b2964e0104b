#pragma once

#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"

namespace floorgrid::test {

/// An asymmetric room of 12 m x 8 m (world metres, origin at its lower-left corner) with a
/// partition wall, a pillar and a notch: no pose looks like another.
inline VectorFloorplan asymmetric_room() {
  VectorFloorplan room;
  const auto wall = [&](double ax, double ay, double bx, double by) {
    room.add_segment({ax, ay}, {bx, by}, "WALLS");
  };
  wall(0, 0, 12, 0);
  wall(12, 0, 12, 5);
  wall(12, 5, 10, 5);  // the notch
  wall(10, 5, 10, 8);
  wall(10, 8, 0, 8);
  wall(0, 8, 0, 0);
  wall(4, 0, 4, 3.5);  // partition
  wall(7, 6, 8.5, 6);  // pillar
  wall(8.5, 6, 8.5, 6.6);
  wall(8.5, 6.6, 7, 6.6);
  wall(7, 6.6, 7, 6);
  return room;
}

/// The plan as a grid of 0.05 m cells with a margin of a metre.
inline OccupancyGrid room_grid(const VectorFloorplan& room) {
  RasterizeOptions options;
  options.wall_thickness = 0.05;
  return rasterize(room, options);
}

/// A scan of `walls` from `pose_in_world` as a log holds it (the odometry poses are the true
/// ones), 361 beams over 180 degrees with 1 cm of range noise and no random readings.
inline LaserScan scan_at(const SegmentRayCaster& walls, const Pose2& pose_in_world,
                         double timestamp, Random& random) {
  LaserSpec spec;
  spec.range_noise_sigma = 0.01;
  spec.random_reading_fraction = 0.0;
  spec.laser_in_robot = Pose2();
  const SimulatedScan scan = simulate_scan(walls, pose_in_world, spec, random);
  return to_laser_scan(scan, pose_in_world, pose_in_world, timestamp);
}

/// A log of scans at `poses` (odometry exact).
inline RobotLog log_along(const VectorFloorplan& room, const std::vector<Pose2>& poses,
                          std::uint64_t seed = 1) {
  const SegmentRayCaster walls(room.segments());
  Random random(seed);
  RobotLog log;
  for (std::size_t i = 0; i < poses.size(); ++i)
    log.scans.push_back(scan_at(walls, poses[i], 0.1 * static_cast<double>(i + 1), random));
  return log;
}

}  // namespace floorgrid::test
