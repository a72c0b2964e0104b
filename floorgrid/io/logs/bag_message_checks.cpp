#include "floorgrid/io/logs/bag_message_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid::io {

namespace {

std::string where(const MessagePlace& place) {
  std::string text = fmt::format("topic {}, message {}", place.topic, place.index);
  if (place.offset > 0)
    text += fmt::format(" (its record at byte {})", place.offset);
  return text;
}

void check_quaternion(const RosQuaternion& q, const std::string& field, const MessagePlace& place) {
  check_bag_value(q.x, kMaxBagAngle, field + ".x", place);
  check_bag_value(q.y, kMaxBagAngle, field + ".y", place);
  check_bag_value(q.z, kMaxBagAngle, field + ".z", place);
  check_bag_value(q.w, kMaxBagAngle, field + ".w", place);
  // A zero quaternion (an unset field) is no rotation: reading it as none would hide it.
  const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!(norm >= 1e-6)) {
    throw InputError(
        fmt::format("{}: is not a rotation (its norm is {}, not 1)", where(place), norm),
        place.file, 0, field);
  }
}

}  // namespace

void check_bag_value(double value, double max_abs, std::string_view field,
                     const MessagePlace& place) {
  if (std::abs(value) <= max_abs)
    return;
  throw InputError(
      fmt::format("{}: must be a finite number within {:g} (got {})", where(place), max_abs, value),
      place.file, 0, std::string(field));
}

void check_odometry(const RosOdometry& o, const MessagePlace& place) {
  check_bag_value(o.position.x, kMaxCoordinate, "pose.pose.position.x", place);
  check_bag_value(o.position.y, kMaxCoordinate, "pose.pose.position.y", place);
  check_quaternion(o.orientation, "pose.pose.orientation", place);
  check_bag_value(o.linear_velocity.x, kMaxBagAngle, "twist.twist.linear.x", place);
  check_bag_value(o.angular_velocity.z, kMaxBagAngle, "twist.twist.angular.z", place);
}

void check_transform(const RosTransform& t, const std::string& field, const MessagePlace& place) {
  check_bag_value(t.translation.x, kMaxCoordinate, field + ".transform.translation.x", place);
  check_bag_value(t.translation.y, kMaxCoordinate, field + ".transform.translation.y", place);
  check_bag_value(t.translation.z, kMaxCoordinate, field + ".transform.translation.z", place);
  check_quaternion(t.rotation, field + ".transform.rotation", place);
}

void check_scan_settings(const RosLaserScan& s, const LaserSettings& manifest,
                         const MessagePlace& place) {
  if (!manifest.start_angle || !manifest.angle_increment) {
    check_bag_value(s.angle_min, kMaxBagAngle, "angle_min", place);
    check_bag_value(s.angle_increment, kMaxBagAngle, "angle_increment", place);
  }
  if (!manifest.min_range)
    check_bag_value(s.range_min, kMaxCoordinate, "range_min", place);
  if (!manifest.max_range)
    check_bag_value(s.range_max, kMaxCoordinate, "range_max", place);
}

}  // namespace floorgrid::io
