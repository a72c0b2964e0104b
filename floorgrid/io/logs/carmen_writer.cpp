#include "floorgrid/io/logs/carmen_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"

namespace floorgrid::io {

namespace {

constexpr double degree = std::numbers::pi / 180.0;
constexpr std::size_t max_beams = 100000;  // read_carmen's limit

// Shortest text that reads back to the same value (std::to_chars' guarantee).
template <typename Number>
void append_number(std::string& out, Number value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  out.append(text, result.ptr);
}

void append_field(std::string& out, double value) {
  out += ' ';
  append_number(out, value);
}

void append_pose(std::string& out, const Pose2& pose) {
  append_field(out, pose.x);
  append_field(out, pose.y);
  append_field(out, pose.theta);
}

void append_tail(std::string& out, double timestamp, const std::string& host) {
  append_field(out, timestamp);
  out += ' ';
  out += host;
  append_field(out, timestamp);  // logger_timestamp: the message's own time
  out += '\n';
}

void append_ranges(std::string& out, const std::vector<float>& ranges) {
  for (float range : ranges) {
    out += ' ';
    append_number(out, range);
  }
}

// The PARAM values one laser side is written with: those of its first old-style-able scan.
struct SideParams {
  std::optional<double> angle_increment;  // radians
  std::optional<double> max_range;        // metres
};

bool fits_old_style(const LaserScan& scan, const SideParams& side) {
  return scan.start_angle == -std::numbers::pi / 2.0 && side.angle_increment &&
         scan.angle_increment == *side.angle_increment && scan.max_range == *side.max_range;
}

bool is_rear(const LaserScan& scan) {
  return scan.type == "RLASER";
}

// The message type each scan is written as (see format_carmen).
std::vector<std::string> written_types(const std::vector<LaserScan>& scans, SideParams& front,
                                       SideParams& rear) {
  for (const LaserScan& scan : scans) {
    SideParams& side = is_rear(scan) ? rear : front;
    if (!side.angle_increment && scan.start_angle == -std::numbers::pi / 2.0 &&
        std::isfinite(scan.angle_increment) && scan.angle_increment > 0.0 &&
        std::isfinite(scan.max_range) && scan.max_range > 0.0) {
      side.angle_increment = scan.angle_increment;
      side.max_range = scan.max_range;
    }
  }
  std::vector<std::string> types;
  types.reserve(scans.size());
  for (const LaserScan& scan : scans) {
    const bool rear_side = is_rear(scan);
    if (fits_old_style(scan, rear_side ? rear : front)) {
      types.push_back(rear_side ? "RLASER" : "FLASER");
    } else {
      types.push_back(rear_side ? "ROBOTLASER2" : "ROBOTLASER1");
    }
  }
  return types;
}

[[noreturn]] void refuse(const std::string& what) {
  throw std::invalid_argument("write_carmen: " + what);
}

void check_timestamp(double timestamp, double& last, const std::string& what) {
  if (!std::isfinite(timestamp) || timestamp <= 0.0) {
    refuse(what + " has timestamp " + std::to_string(timestamp) + ": must be finite and > 0");
  }
  if (timestamp < last)
    refuse(what + " goes back in time (timestamps must not decrease)");
  last = timestamp;
}

void check_log(const RobotLog& log, const std::vector<std::string>& types,
               const CarmenWriteOptions& options) {
  if (options.host.empty() || options.host.find_first_of(" \t\r\n\f\v") != std::string::npos) {
    refuse("host must be one word (got '" + options.host + "')");
  }
  if (options.gzip_level < 1 || options.gzip_level > 9)
    refuse("gzip_level must be 1..9");
  double last_odometry = 0.0;
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    check_timestamp(log.odometry[i].timestamp, last_odometry,
                    "odometry[" + std::to_string(i) + "]");
  }
  std::map<std::string, double> last_scan;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const LaserScan& scan = log.scans[i];
    const std::string what = "scan[" + std::to_string(i) + "]";
    check_timestamp(scan.timestamp, last_scan[types[i]], what);
    if (scan.ranges.empty() || scan.ranges.size() > max_beams) {
      refuse(what + " has " + std::to_string(scan.ranges.size()) + " readings: must be 1..100000");
    }
    if (!std::isfinite(scan.start_angle) || !std::isfinite(scan.angle_increment) ||
        scan.angle_increment == 0.0 || !std::isfinite(scan.max_range) || scan.max_range <= 0.0) {
      refuse(what +
             " needs a finite start angle, a finite non-zero increment and a finite "
             "max range > 0");
    }
  }
}

void append_header(std::string& out) {
  out +=
      "# CARMEN Logfile\n"
      "# file format is one message per line\n"
      "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n"
      "# message formats defined: PARAM ODOM FLASER RLASER ROBOTLASER1 ROBOTLASER2\n"
      "# PARAM param_name param_value\n"
      "# ODOM x y theta tv rv accel\n"
      "# FLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta\n"
      "# RLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta\n"
      "# ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range "
      "accuracy remission_mode num_readings [range_readings] num_remissions [remissions] "
      "laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv forward_safety_dist "
      "side_safety_dist turn_axis\n"
      "# written by floorgrid\n";
}

void append_param(std::string& out, const char* name, const std::string& value, double timestamp,
                  const std::string& host) {
  out += "PARAM ";
  out += name;
  out += ' ';
  out += value;
  append_tail(out, timestamp, host);
}

std::string number_text(double value) {
  std::string text;
  append_number(text, value);
  return text;
}

// The resolution PARAM in degrees: the fewest digits whose value, read back and converted as
// read_carmen does (degrees * pi/180), gives exactly `increment` (0.5, not 0.49999999999999994);
// when no decimal text does, the shortest text of increment / (pi/180).
std::string degrees_text(double increment) {
  for (int digits = 1; digits <= 17; ++digits) {
    char text[64];
    const auto result = std::to_chars(text, text + sizeof(text), increment / degree,
                                      std::chars_format::general, digits);
    double value = 0.0;
    std::from_chars(text, result.ptr, value);
    if (value * degree == increment)
      return std::string(text, result.ptr);
  }
  return number_text(increment / degree);
}

void append_odometry(std::string& out, const OdometryReading& odometry, const std::string& host) {
  out += "ODOM";
  append_pose(out, odometry.pose);
  append_field(out, odometry.tv);
  append_field(out, odometry.rv);
  append_field(out, odometry.accel);
  append_tail(out, odometry.timestamp, host);
}

void append_scan(std::string& out, const LaserScan& scan, const std::string& type,
                 const std::string& host) {
  out += type;
  if (type == "FLASER" || type == "RLASER") {
    out += ' ';
    append_number(out, scan.ranges.size());
    append_ranges(out, scan.ranges);
    append_pose(out, scan.laser_pose);
    append_pose(out, scan.robot_pose);
  } else {
    const double fov = scan.angle_increment * static_cast<double>(scan.ranges.size() - 1);
    out += " 0";  // laser_type: SICK LMS, as CARMEN guesses for old logs
    append_field(out, scan.start_angle);
    append_field(out, fov);
    append_field(out, scan.angle_increment);
    append_field(out, scan.max_range);
    out += " 0.01 0 ";  // accuracy (CARMEN's guess), remission_mode off
    append_number(out, scan.ranges.size());
    append_ranges(out, scan.ranges);
    out += " 0";  // no remissions
    append_pose(out, scan.laser_pose);
    append_pose(out, scan.robot_pose);
    out += " 0 0 0 0 0";  // tv rv forward_safety_dist side_safety_dist turn_axis
  }
  append_tail(out, scan.timestamp, host);
}

std::string gzip(const std::string& text, int level) {
  z_stream stream{};
  if (deflateInit2(&stream, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("write_carmen: zlib deflateInit2 failed");
  }
  std::string out(deflateBound(&stream, static_cast<uLong>(text.size())), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  stream.avail_in = static_cast<uInt>(text.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  const int result = deflate(&stream, Z_FINISH);
  const std::size_t written = stream.total_out;
  deflateEnd(&stream);
  if (result != Z_STREAM_END)
    throw std::runtime_error("write_carmen: zlib deflate failed");
  out.resize(written);
  return out;
}

}  // namespace

std::string format_carmen(const RobotLog& log, const CarmenWriteOptions& options) {
  SideParams front;
  SideParams rear;
  const std::vector<std::string> types = written_types(log.scans, front, rear);
  check_log(log, types, options);

  // Merge by (timestamp, source line, odometry first, list order): a log read from a file
  // keeps its file order on equal timestamps.
  using Entry = std::tuple<double, std::size_t, int, std::size_t>;
  std::vector<Entry> order;
  order.reserve(log.odometry.size() + log.scans.size());
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    order.emplace_back(log.odometry[i].timestamp, log.odometry[i].line, 0, i);
  }
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    order.emplace_back(log.scans[i].timestamp, log.scans[i].line, 1, i);
  }
  std::sort(order.begin(), order.end());

  std::string out;
  std::size_t beams = 0;
  for (const LaserScan& scan : log.scans)
    beams += scan.ranges.size();
  out.reserve(1024 + log.odometry.size() * 96 + log.scans.size() * 160 + beams * 8);
  append_header(out);
  const double param_time = order.empty() ? 0.0 : std::get<0>(order.front());
  if (front.angle_increment) {
    append_param(out, "laser_front_laser_resolution", degrees_text(*front.angle_increment),
                 param_time, options.host);
    append_param(out, "robot_front_laser_max", number_text(*front.max_range), param_time,
                 options.host);
  }
  if (rear.angle_increment) {
    append_param(out, "laser_rear_laser_resolution", degrees_text(*rear.angle_increment),
                 param_time, options.host);
    append_param(out, "robot_rear_laser_max", number_text(*rear.max_range), param_time,
                 options.host);
  }
  for (const auto& [timestamp, line, kind, index] : order) {
    if (kind == 0) {
      append_odometry(out, log.odometry[index], options.host);
    } else {
      append_scan(out, log.scans[index], types[index], options.host);
    }
  }
  return out;
}

void write_carmen(const RobotLog& log, const std::filesystem::path& path,
                  const CarmenWriteOptions& options) {
  const std::string text = format_carmen(log, options);
  const std::string extension = path.extension().string();
  const bool compress = extension == ".gz" || extension == ".GZ";
  write_file_atomically(path, compress ? gzip(text, options.gzip_level) : text);
}

}  // namespace floorgrid::io
