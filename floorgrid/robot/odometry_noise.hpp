#pragma once

#include <cstdint>

#include "floorgrid/robot/motion_model.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// Turns the SLAM-corrected poses of a "corrected" log (the Radish sets) back into noisy
/// odometry to test tracking: the motion between consecutive scans' robot poses gets noise
/// sampled from the odometry model with `noise` (alpha1..alpha4) and the noisy motions are
/// chained from the first pose. Each scan's laser pose keeps its offset from the robot pose.
/// Only the scans' poses change (the localizer reads its odometry from them); the ODOM
/// messages are left as they are. Deterministic for a seed.
RobotLog add_odometry_noise(const RobotLog& log, const MotionNoise& noise, std::uint64_t seed);

}  // namespace floorgrid
