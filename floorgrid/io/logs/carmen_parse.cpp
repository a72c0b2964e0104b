#include "floorgrid/io/logs/carmen_parse.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <system_error>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid::io {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string in_quotes(std::string_view token) {
  constexpr std::size_t shown = 40;
  std::string text(token.substr(0, shown));
  if (token.size() > shown)
    text += "...";
  return "'" + text + "'";
}

}  // namespace

bool parse_number(std::string_view token, double& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  // strtod (CARMEN's reader) takes a leading '+', from_chars does not.
  if (first != last && *first == '+') {
    ++first;
    if (first != last && (*first == '-' || *first == '+'))
      return false;
  }
  if (first == last)
    return false;
  const auto [end, error] = std::from_chars(first, last, value);
  if (end != last)
    return false;
  if (error == std::errc::result_out_of_range) {
    // Overflow or underflow: take strtod's answer (+-inf, or the nearest subnormal or zero).
    const std::string copy(first, last);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return error == std::errc();
}

FieldCursor::FieldCursor(std::string_view text, std::string_view file, std::size_t line)
    : text_(text), file_(file), line_(line) {}

void FieldCursor::fail(const std::string& message, std::string_view field) const {
  throw InputError(message, std::string(file_), static_cast<long>(line_), std::string(field));
}

void FieldCursor::fail_missing(std::string_view field) const {
  fail("line ends early after " + std::to_string(fields_read_) +
           " fields (truncated line, or fewer fields than its count says)",
       field);
}

std::string_view FieldCursor::next_token(std::string_view field) {
  while (position_ < text_.size() && is_space(text_[position_]))
    ++position_;
  if (position_ == text_.size())
    fail_missing(field);
  const std::size_t start = position_;
  while (position_ < text_.size() && !is_space(text_[position_]))
    ++position_;
  ++fields_read_;
  return text_.substr(start, position_ - start);
}

std::string_view FieldCursor::word(std::string_view field) {
  return next_token(field);
}

double FieldCursor::number(std::string_view field) {
  const std::string_view token = next_token(field);
  double value = 0.0;
  if (!parse_number(token, value))
    fail("not a number: " + in_quotes(token), field);
  return value;
}

double FieldCursor::finite(std::string_view field, double max_abs) {
  const double value = number(field);
  if (!(std::abs(value) <= max_abs)) {
    std::ostringstream message;
    message << "must be a finite number within " << max_abs << " (got " << value << ")";
    fail(message.str(), field);
  }
  return value;
}

double FieldCursor::indexed_number(std::string_view prefix, std::size_t index) {
  while (position_ < text_.size() && is_space(text_[position_]))
    ++position_;
  if (position_ == text_.size())
    fail_missing(std::string(prefix) + " " + std::to_string(index));
  const std::size_t start = position_;
  while (position_ < text_.size() && !is_space(text_[position_]))
    ++position_;
  ++fields_read_;
  const std::string_view token = text_.substr(start, position_ - start);
  double value = 0.0;
  if (!parse_number(token, value)) {
    fail("not a number: " + in_quotes(token), std::string(prefix) + " " + std::to_string(index));
  }
  return value;
}

long FieldCursor::integer(std::string_view field, long min, long max) {
  const std::string_view token = next_token(field);
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+')
    ++first;
  long value = 0;
  const auto [end, error] = std::from_chars(first, last, value);
  if (end != last || error == std::errc::invalid_argument || first == last) {
    fail("not an integer: " + in_quotes(token), field);
  }
  if (error == std::errc::result_out_of_range || value < min || value > max) {
    fail("must be an integer from " + std::to_string(min) + " to " + std::to_string(max) +
             " (got " + in_quotes(token) + ")",
         field);
  }
  return value;
}

bool FieldCursor::next_is_number() {
  while (position_ < text_.size() && is_space(text_[position_]))
    ++position_;
  std::size_t end = position_;
  while (end < text_.size() && !is_space(text_[end]))
    ++end;
  double value = 0.0;
  return end == position_ || parse_number(text_.substr(position_, end - position_), value);
}

bool FieldCursor::at_end() {
  while (position_ < text_.size() && is_space(text_[position_]))
    ++position_;
  return position_ == text_.size();
}

void FieldCursor::expect_end() {
  if (at_end())
    return;
  std::size_t extra = 0;
  while (!at_end()) {
    next_token({});
    ++extra;
  }
  fail(std::to_string(extra) + " field(s) more than the message has (" +
           std::to_string(fields_read_) + " in all): is its count right?",
       "end of line");
}

namespace {

Pose2 read_pose(FieldCursor& fields, std::string_view x, std::string_view y,
                std::string_view theta) {
  // A pose is metres within kMaxCoordinate and a finite heading (NaN would poison every
  // filter silently).
  Pose2 pose;
  pose.x = fields.finite(x, kMaxCoordinate);
  pose.y = fields.finite(y, kMaxCoordinate);
  pose.theta = fields.finite(theta, 1e6);
  return pose;
}

// Every message ends in `timestamp host logger_timestamp`. CARMEN's own readers need the host
// (they copy the word after the timestamp) and its logplayer the logger timestamp, so a line
// without them is not a CARMEN log line: strict, no "old style" without them.
double read_tail(FieldCursor& fields) {
  // A count one too large shifts every field after the readings: the host name lands where the
  // timestamp should be.
  if (!fields.next_is_number()) {
    fields.fail(
        "not a number where the timestamp should be: does the line hold fewer readings "
        "than its count says?",
        "timestamp");
  }
  const double timestamp = fields.number("timestamp");
  fields.word("host");
  fields.number("logger_timestamp");
  fields.expect_end();
  return timestamp;
}

void read_ranges(FieldCursor& fields, std::size_t count, std::vector<float>& ranges) {
  ranges.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    ranges[i] = static_cast<float>(fields.indexed_number("range", i + 1));
  }
}

}  // namespace

OdometryReading parse_odom(FieldCursor& fields) {
  OdometryReading odometry;
  odometry.pose = read_pose(fields, "x", "y", "theta");
  odometry.tv = fields.number("tv");
  odometry.rv = fields.number("rv");
  odometry.accel = fields.number("accel");
  odometry.timestamp = read_tail(fields);
  return odometry;
}

LaserScan parse_old_laser(FieldCursor& fields) {
  LaserScan scan;
  const long beams = fields.integer("beam count", 1, max_carmen_beams);
  read_ranges(fields, static_cast<std::size_t>(beams), scan.ranges);
  scan.laser_pose = read_pose(fields, "laser_x", "laser_y", "laser_theta");
  scan.robot_pose = read_pose(fields, "robot_x", "robot_y", "robot_theta");
  scan.timestamp = read_tail(fields);
  return scan;
}

LaserScan parse_robot_laser(FieldCursor& fields) {
  LaserScan scan;
  fields.integer("laser_type", -1000000, 1000000);
  scan.start_angle = fields.number("start_angle");
  fields.number("fov");
  scan.angle_increment = fields.number("angular_resolution");
  scan.max_range = fields.number("maximum_range");
  fields.number("accuracy");
  fields.integer("remission_mode", -1000000, 1000000);
  const long beams = fields.integer("num_readings", 1, max_carmen_beams);
  read_ranges(fields, static_cast<std::size_t>(beams), scan.ranges);
  const long remissions = fields.integer("num_remissions", 0, max_carmen_beams);
  for (long i = 0; i < remissions; ++i) {
    fields.indexed_number("remission", static_cast<std::size_t>(i) + 1);
  }
  scan.laser_pose = read_pose(fields, "laser_x", "laser_y", "laser_theta");
  scan.robot_pose = read_pose(fields, "robot_x", "robot_y", "robot_theta");
  fields.number("tv");
  fields.number("rv");
  fields.number("forward_safety_dist");
  fields.number("side_safety_dist");
  fields.number("turn_axis");
  scan.timestamp = read_tail(fields);
  return scan;
}

bool is_old_laser_type(std::string_view type) {
  return type == "FLASER" || type == "RLASER";
}

bool is_robot_laser_type(std::string_view type) {
  return type == "ROBOTLASER1" || type == "ROBOTLASER2";
}

}  // namespace floorgrid::io
