#pragma once

#include <cstddef>
#include <map>
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

/// Laser settings given from outside (the dataset manifest's `laser:` map). Each one given
/// takes precedence over what the log says (PARAM lines, a message's own fields, guesses).
struct LaserSettings {
  std::optional<double> max_range;        ///< metres, > 0
  std::optional<double> min_range;        ///< metres, >= 0 and < max_range
  std::optional<double> start_angle;      ///< radians, relative to the laser pose
  std::optional<double> angle_increment;  ///< radians, non-zero
};

/// Checks `settings`; throws InputError naming the field (`laser.max_range`, ...) when one is
/// out of range or not finite.
void validate_laser_settings(const LaserSettings& settings);

/// Where a laser setting came from, highest precedence first.
enum class SettingSource {
  manifest,  ///< LaserSettings given by the caller
  message,   ///< the scan message's own field (ROBOTLASER1)
  param,     ///< a PARAM line of the log
  guess,     ///< CARMEN's guess from the beam count, or its fixed default
};

/// "manifest", "message", "param" or "guess".
const char* to_string(SettingSource source);

/// One laser setting as it was used, and where it came from.
struct UsedSetting {
  double value = 0.0;                           ///< metres or radians, as the setting says
  SettingSource source = SettingSource::guess;  ///< where the value came from
  std::string detail;  ///< e.g. the PARAM's name, or how the guess was made
  bool operator==(const UsedSetting&) const = default;
};

/// A distinct laser configuration met in a log, and how many scans used it.
struct LaserConfigUsage {
  std::string type;             ///< message type (FLASER, RLASER, ROBOTLASER1, ...)
  std::size_t beams = 0;        ///< readings per scan
  UsedSetting start_angle;      ///< radians
  UsedSetting angle_increment;  ///< radians
  UsedSetting max_range;        ///< metres
  UsedSetting min_range;        ///< metres
  std::size_t scans = 0;        ///< scans kept with exactly this configuration
};

/// Lines of one message type in a log and what became of them.
/// lines = kept + skipped_zero_timestamp + skipped_backwards_timestamp + not_data.
struct MessageTypeCount {
  std::size_t lines = 0;  ///< lines of this type
  std::size_t kept = 0;   ///< messages read into the log
  /// skipped: timestamp zero, negative or not finite (not a time at all)
  std::size_t skipped_zero_timestamp = 0;
  /// skipped: timestamp strictly earlier than the last kept message of the same type
  std::size_t skipped_backwards_timestamp = 0;
  /// lines of a type that carries no odometry or scan (PARAM, NEFF, comments, unknown types)
  std::size_t not_data = 0;
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

/// What a log held and how it was read.
struct RobotLogSummary {
  std::string source;     ///< the file read, or empty
  std::size_t lines = 0;  ///< lines in the file
  /// Per message type as named in the file; comment lines under "#", blank lines under
  /// "(empty)", unknown types under their own name.
  std::map<std::string, MessageTypeCount> messages;
  std::map<std::string, std::string> params;          ///< PARAM name -> value (the last one)
  std::map<std::size_t, std::size_t> beams_per_scan;  ///< beam count -> kept scans
  std::vector<LaserConfigUsage> laser_configs;        ///< distinct configurations, first seen first
  RangeCounts ranges;                                 ///< readings of the kept scans by kind
  double first_timestamp = 0.0;  ///< seconds, earliest kept odometry or scan timestamp
  double last_timestamp = 0.0;   ///< seconds, latest kept odometry or scan timestamp
  double duration = 0.0;         ///< seconds, last_timestamp - first_timestamp
};

/// A recorded robot run: odometry and laser scans, each in file order (so timestamps never
/// decrease within either), and a summary of how it was read.
struct RobotLog {
  std::vector<OdometryReading> odometry;  ///< in file order
  std::vector<LaserScan> scans;           ///< in file order
  RobotLogSummary summary;                ///< counts and settings used
};

}  // namespace floorgrid
