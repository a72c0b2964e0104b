#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

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
  /// the readings themselves: they contradicted a PARAM or a guess (see RobotLogSummary::warnings)
  readings,
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
  /// What was read other than the file says: a log read in line order because no scan had a
  /// valid timestamp, a max range the readings contradicted. One sentence each.
  std::vector<std::string> warnings;
};

}  // namespace floorgrid
