#pragma once

#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// One odometry message: the robot's pose as its odometry saw it (in "corrected" logs, the
/// SLAM-corrected pose), with the velocities the log carries.
struct OdometryReading {
  Pose2 pose;              ///< metres and radians, in the log's odometry frame
  double tv = 0.0;         ///< translational velocity, m/s
  double rv = 0.0;         ///< rotational velocity, rad/s
  double accel = 0.0;      ///< acceleration, m/s^2
  double timestamp = 0.0;  ///< seconds
  std::size_t line = 0;    ///< 1-based line in the file it was read from; 0 when not read
};

/// What one range reading of a scan means.
enum class RangeKind {
  hit,  ///< finite, > 0, >= min_range and < max_range: the beam hit something there
  /// >= max_range (including +inf): nothing within range. Compared at float precision, the
  /// readings' own, so a reading printed as the max range is at it.
  no_return,
  too_close,  ///< 0 <= r < min_range, or exactly 0: no usable distance
  invalid,    ///< NaN or negative: no usable distance (counted apart, as a sign of a bad log)
};

/// "hit", "no_return", "too_close" or "invalid".
const char* to_string(RangeKind kind);

/// One laser scan with the settings that give each beam its angle, and the poses at the scan.
struct LaserScan {
  std::string type;  ///< the message it came from: FLASER, RLASER, ROBOTLASER1, ...
  /// radians, angle of beam 0 relative to the laser pose (CARMEN: -pi/2)
  double start_angle = -std::numbers::pi / 2.0;
  double angle_increment = 0.0;  ///< radians between neighbouring beams
  double max_range = 80.0;       ///< metres; readings at or above it are "no return"
  double min_range = 0.0;        ///< metres; readings below it are "too close"
  std::vector<float> ranges;     ///< metres, one per beam
  /// Pose of the laser in the odometry frame at the scan. A rear laser's pose already faces
  /// backwards (its theta is the robot's plus pi), so beam angles need no special case.
  Pose2 laser_pose;
  Pose2 robot_pose;        ///< the robot's odometry pose at the scan
  double timestamp = 0.0;  ///< seconds
  std::size_t line = 0;    ///< 1-based line in the file it was read from; 0 when not read

  /// Angle of beam `i` relative to the laser pose: start_angle + i * angle_increment (radians).
  double angle(std::size_t i) const {
    return start_angle + static_cast<double>(i) * angle_increment;
  }
  /// What reading `i` means (see RangeKind).
  RangeKind range_kind(std::size_t i) const;
  /// True when reading `i` is a hit: finite, > 0, >= min_range and < max_range.
  bool is_return(std::size_t i) const { return range_kind(i) == RangeKind::hit; }
};

/// Range readings of the kept scans by kind; total = hits + no_return + too_close + invalid.
struct RangeCounts {
  std::size_t total = 0;      ///< readings
  std::size_t hits = 0;       ///< RangeKind::hit
  std::size_t no_return = 0;  ///< RangeKind::no_return (at or above max range)
  std::size_t too_close = 0;  ///< RangeKind::too_close
  std::size_t invalid = 0;    ///< RangeKind::invalid (NaN or negative)
};

/// Counts the readings of `scans` by RangeKind.
RangeCounts count_ranges(const std::vector<LaserScan>& scans);

/// A recorded robot run: odometry and laser scans, each in file order (so timestamps never
/// decrease within either.
struct RobotLog {
  std::vector<OdometryReading> odometry;  ///< in file order
  std::vector<LaserScan> scans;           ///< in file order
};

}  // namespace floorgrid
