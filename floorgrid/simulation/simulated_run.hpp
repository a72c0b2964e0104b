#pragma once

#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"
#include "floorgrid/simulation/robot_tour.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
#include "floorgrid/simulation/simulation_preset.hpp"
#include "floorgrid/simulation/slam_map.hpp"

namespace floorgrid {

/// The preset's laser as the simulator fires it: its beams spread evenly over the field of
/// view, mounted `laser_forward_offset` ahead of the robot's centre.
LaserSpec preset_laser(const SimulationPreset& preset);

/// A robot's recorded run through a world: what the log holds and what the mapper takes.
struct SimulatedRun {
  RobotLog log;                           ///< noisy odometry every tick, a scan every scan period
  std::vector<SlamMapInput> slam_inputs;  ///< each scan with its TRUE laser pose
  LaserScanCounts counts;                 ///< the beams of every scan, by what they met
  Pose2 final_odometry;                   ///< the odometry's last pose (its frame starts at 0)
};

/// Drives `trajectory` (true poses in the world, one per odometry tick) through the world of
/// `caster`: noisy odometry (the preset's alpha, starting at the odometry frame's origin) every
/// tick and a scan every `scan_period`, both stamped with the noisy odometry as a real robot's
/// log would be. Deterministic for the two random states.
SimulatedRun simulate_run(const std::vector<TimedPose>& trajectory, const SegmentRayCaster& caster,
                          const SimulationPreset& preset, Random& odometry_random,
                          Random& laser_random);

}  // namespace floorgrid
