#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/io/logs/bag_file.hpp"

namespace floorgrid::io {

/// std_msgs/Header (ROS 1 also has a sequence number, dropped here).
struct RosHeader {
  std::int64_t stamp_ns = 0;  ///< sec * 1e9 + nsec
  std::string frame_id;
};

/// geometry_msgs/Vector3 or Point.
struct RosVector3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

/// geometry_msgs/Quaternion.
struct RosQuaternion {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};

/// sensor_msgs/LaserScan. Ranges as sent: per REP 117, +inf is "no return within range", -inf
/// "too close" and NaN an invalid reading.
struct RosLaserScan {
  RosHeader header;
  float angle_min = 0.0f;        ///< radians, beam 0 in the laser's frame
  float angle_max = 0.0f;        ///< radians, the last beam
  float angle_increment = 0.0f;  ///< radians between beams
  float time_increment = 0.0f;   ///< seconds between beams
  float scan_time = 0.0f;        ///< seconds between scans
  float range_min = 0.0f;        ///< metres
  float range_max = 0.0f;        ///< metres
  std::vector<float> ranges;     ///< metres
  std::vector<float> intensities;
};

/// nav_msgs/Odometry: the pose of `child_frame_id` in `header.frame_id` (covariances dropped).
struct RosOdometry {
  RosHeader header;
  std::string child_frame_id;
  RosVector3 position;
  RosQuaternion orientation;
  RosVector3 linear_velocity;   ///< in child_frame_id, m/s
  RosVector3 angular_velocity;  ///< in child_frame_id, rad/s
};

/// geometry_msgs/TransformStamped: the pose of `child_frame_id` in `header.frame_id`.
struct RosTransform {
  RosHeader header;
  std::string child_frame_id;
  RosVector3 translation;
  RosQuaternion rotation;
};

/// Where a payload came from, for errors: the file and the byte offset of its record.
struct PayloadSource {
  std::string_view file;
  std::uint64_t offset = 0;
  std::string_view topic;
};

/// Decodes a sensor_msgs/LaserScan payload in either encoding. Throws InputError naming the
/// file, the byte offset and the topic when the payload is shorter than its fields say (an
/// array whose length lies), has bytes left over, or is CDR big-endian.
RosLaserScan decode_laser_scan(std::span<const std::uint8_t> data, MessageEncoding encoding,
                               const PayloadSource& source);
/// Decodes a nav_msgs/Odometry payload; throws as decode_laser_scan.
RosOdometry decode_odometry(std::span<const std::uint8_t> data, MessageEncoding encoding,
                            const PayloadSource& source);
/// Decodes a tf2_msgs/TFMessage (ROS 1 also tf/tfMessage) payload; throws as decode_laser_scan.
std::vector<RosTransform> decode_tf_message(std::span<const std::uint8_t> data,
                                            MessageEncoding encoding, const PayloadSource& source);

/// The message kinds the log reader uses, told by a topic's type name in either ROS spelling
/// ("sensor_msgs/LaserScan", "sensor_msgs/msg/LaserScan").
enum class RosMessageKind { laser_scan, odometry, tf, other };

/// The kind of a type name.
RosMessageKind ros_message_kind(std::string_view type);

}  // namespace floorgrid::io
