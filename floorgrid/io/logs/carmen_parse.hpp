#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "floorgrid/io/logs/robot_log_summary.hpp"

namespace floorgrid::io {

/// Walks the whitespace-separated fields of one CARMEN log line. Every read names the field it
/// expects, so that a missing or malformed field is an InputError naming the file, the line and
/// the field. Numbers are parsed with std::from_chars (no locale, no iostreams).
class FieldCursor {
 public:
  /// A cursor over `text` (one line without its end-of-line), from `file`'s line `line`.
  FieldCursor(std::string_view text, std::string_view file, std::size_t line);

  /// The next field as text; throws when the line has ended.
  std::string_view word(std::string_view field);
  /// The next field as a number (strtod syntax: also "nan", "inf", a leading '+').
  double number(std::string_view field);
  /// The next field as a finite number within `max_abs`: a pose's coordinate or heading.
  double finite(std::string_view field, double max_abs);
  /// The next field as an integer in [min, max].
  long integer(std::string_view field, long min, long max);
  /// The next field as a number, named "<prefix> <index>" (e.g. "range 17") only on error.
  double indexed_number(std::string_view prefix, std::size_t index);
  /// Whether the next field (if any) reads as a number.
  bool next_is_number();
  /// Whether no field is left.
  bool at_end();
  /// Throws unless every field was read.
  void expect_end();
  /// Throws InputError(message, file, line, field).
  [[noreturn]] void fail(const std::string& message, std::string_view field) const;

 private:
  std::string_view next_token(std::string_view field);
  [[noreturn]] void fail_missing(std::string_view field) const;

  std::string_view text_;
  std::size_t position_ = 0;
  std::size_t fields_read_ = 0;
  std::string_view file_;
  std::size_t line_;
};

/// Parses a number with strtod's syntax; false when `token` is not wholly a number.
bool parse_number(std::string_view token, double& value);

/// The largest beam (or remission) count accepted in one message.
inline constexpr long max_carmen_beams = 100000;

/// Reads `ODOM x y theta tv rv accel timestamp host logger_timestamp` after the type.
OdometryReading parse_odom(FieldCursor& fields);

/// Reads `FLASER n r1..rn laser_x laser_y laser_theta robot_x robot_y robot_theta timestamp
/// host logger_timestamp` (RLASER alike) after the type. The scan's angle and range settings
/// are left as defaults: they come from PARAMs, the manifest or CARMEN's guess.
LaserScan parse_old_laser(FieldCursor& fields);

/// Reads `ROBOTLASER1 laser_type start_angle fov angular_resolution maximum_range accuracy
/// remission_mode num_readings readings.. num_remissions remissions.. laser_x laser_y
/// laser_theta robot_x robot_y robot_theta tv rv forward_safety_dist side_safety_dist
/// turn_axis timestamp host logger_timestamp` after the type, with its own settings.
LaserScan parse_robot_laser(FieldCursor& fields);

/// True for the types read as laser scans without settings (FLASER, RLASER).
bool is_old_laser_type(std::string_view type);
/// True for the types read as laser scans with their own settings (ROBOTLASER1, ROBOTLASER2).
bool is_robot_laser_type(std::string_view type);

}  // namespace floorgrid::io
