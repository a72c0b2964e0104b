#pragma once

#include <filesystem>

#include "floorgrid/io/logs/robot_log_summary.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid::io {

/// Options of read_carmen.
struct CarmenReadOptions {
  /// Laser settings from the dataset manifest (`laser:`); each one given overrides the log's
  /// PARAMs, a ROBOTLASER1's own fields and CARMEN's guesses, for every scan.
  LaserSettings laser;
};

/// A CARMEN log read: the run, and how it was read.
struct CarmenLog : RobotLog {
  RobotLogSummary summary;  ///< counts and settings used
};

/// Reads a CARMEN text log, plain or gzip-compressed (told by content, not by name).
///
/// Read as data: `ODOM`, `FLASER` and `RLASER` (old style: beam i at -pi/2 + i * inc relative
/// to the laser pose; a rear laser's pose in the log already faces backwards), and
/// `ROBOTLASER1`/`ROBOTLASER2` (with their own start angle, resolution and maximum range).
/// Every message must end in `timestamp host logger_timestamp`, as CARMEN's own readers need.
///
/// Laser settings, highest precedence first: `options.laser` (the manifest); a ROBOTLASER's
/// own fields; PARAMs (`laser_front_laser_resolution` in degrees, max range from
/// `laser_front_laser_maxrange` or else CARMEN's `robot_front_laser_max`; `rear` for RLASER);
/// CARMEN's guess (180/181 beams -> 1 degree, 360/361 -> 0.5, 400/401 -> 0.25, else
/// pi/(n-1); max range 80 m; no minimum range). A PARAM takes effect from its line on, as in
/// CARMEN's log player.
///
/// Skipped and counted per type in `summary.messages`: PARAM (kept in `summary.params`), NEFF,
/// `#` comments, blank lines, unknown types (RAWLASER*, TRUEPOS, ...), and ODOM/laser messages
/// whose timestamp is zero, negative or not finite, or strictly earlier than the last kept
/// message of the same type (equal timestamps are kept). So the kept timestamps never
/// decrease within a type. Except: when no laser message has a valid timestamp (a log written
/// with every stamp 0), the zero-stamped messages are read in line order, with a warning.
///
/// The readings win over a max range from a PARAM or a guess that they contradict (never over the
/// manifest's or a ROBOTLASER's own): when more than 0.1% of them (at least 20) lie beyond it,
/// other than at the longest value, the max range becomes that longest value; when at least as
/// many sit at one longest value below it (a saturation code, as ACES's 50 m under the 80 m
/// guess), the max range becomes that value, so they count as no return. Each change is a
/// warning in `summary.warnings` and the setting's source becomes `readings`.
///
/// Throws InputError naming the file, the 1-based line and the field when the file is missing,
/// a line is truncated or has extra fields, a number is malformed, a beam count is not in
/// 1..100000, a gzip stream is corrupt or ends early, a used PARAM is not a positive number, or
/// the log has no laser scan to localize with.
CarmenLog read_carmen_log(const std::filesystem::path& path, const CarmenReadOptions& options = {});

/// read_carmen_log without the summary.
RobotLog read_carmen(const std::filesystem::path& path, const CarmenReadOptions& options = {});

}  // namespace floorgrid::io
