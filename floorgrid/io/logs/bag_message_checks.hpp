#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "floorgrid/io/logs/robot_log_summary.hpp"
#include "floorgrid/io/logs/ros_messages.hpp"

namespace floorgrid::io {

/// Where a decoded message came from, for errors: the file, the topic, the message's number on
/// it and its record's byte offset.
struct MessagePlace {
  std::string file;
  std::string topic;
  std::size_t index = 0;     ///< 1-based, among the messages of its topic
  std::uint64_t offset = 0;  ///< its record's byte offset (0: unknown, a database row)
};

/// The values read from a bag are checked as the CARMEN reader checks a log's: a coordinate is a
/// finite number within kMaxCoordinate metres, an angle and a velocity finite within this.
inline constexpr double kMaxBagAngle = 1e6;

/// Throws InputError naming the file, `field` and `place` (topic, message, byte) unless
/// |value| <= max_abs (NaN and infinities never are).
void check_bag_value(double value, double max_abs, std::string_view field,
                     const MessagePlace& place);

/// Checks a nav_msgs/Odometry's position (x, y), orientation and velocities.
void check_odometry(const RosOdometry& odometry, const MessagePlace& place);

/// Checks one transform of a TFMessage (`field` names it: "transforms[2]"): translation and
/// rotation.
void check_transform(const RosTransform& transform, const std::string& field,
                     const MessagePlace& place);

/// Checks the LaserScan settings a run takes from the message rather than from `manifest`
/// (dataset.yaml's laser:): angle_min and angle_increment unless it gives both angles,
/// range_min and range_max unless it gives each.
void check_scan_settings(const RosLaserScan& scan, const LaserSettings& manifest,
                         const MessagePlace& place);

}  // namespace floorgrid::io
