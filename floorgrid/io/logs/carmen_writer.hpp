#pragma once

#include <filesystem>
#include <string>

#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid::io {

/// Options of write_carmen.
struct CarmenWriteOptions {
  std::string host = "floorgrid";  ///< the host field of every message: one word
  int gzip_level = 6;              ///< zlib level 1..9, used when the path ends in ".gz"
};

/// Formats `log` as CARMEN text: a header comment naming the message formats, PARAM lines
/// (`laser_front_laser_resolution` in degrees and `robot_front_laser_max` in metres, and the
/// `rear` ones when there are RLASER scans), then ODOM and laser lines merged in timestamp
/// order (file order on ties), each ending in `timestamp host logger_timestamp`.
///
/// A scan is written as FLASER (RLASER for type "RLASER") when its start angle is -pi/2 and
/// its increment and max range equal the PARAMs' (those of the first such scan of its side);
/// any other scan is written as ROBOTLASER1 (ROBOTLASER2 for the rear side), which carries its
/// own settings. min_range has no place in CARMEN's format and is not written.
/// Numbers are printed with the fewest digits that read back to the same float or double, so
/// read_carmen gives back identical poses, ranges and timestamps (the increment via its PARAM
/// in degrees to within an ulp or two). Non-finite ranges are written as "nan"/"inf".
///
/// Throws std::invalid_argument when the log cannot be written faithfully: a timestamp that is
/// not finite and > 0, timestamps decreasing within the odometry or within the scans of one
/// type, a scan without readings or with more than 100000, or a bad option.
std::string format_carmen(const RobotLog& log, const CarmenWriteOptions& options = {});

/// Writes format_carmen(log) to `path` atomically (temporary file + rename), gzip-compressed
/// when the path ends in ".gz". Throws InputError naming the file when it cannot be written.
void write_carmen(const RobotLog& log, const std::filesystem::path& path,
                  const CarmenWriteOptions& options = {});

}  // namespace floorgrid::io
