#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/robot_log_summary.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid::io {

/// What of a bag makes the run: dataset.yaml's `log_topics` and `log_frames`, and `laser`.
struct BagLogOptions {
  /// `log_topics.scan`: the sensor_msgs/LaserScan topic; found when the bag has exactly one.
  std::optional<std::string> scan_topic;
  /// `log_topics.odom`: the nav_msgs/Odometry topic; found when the bag has exactly one; with
  /// none, odometry is the `odom` -> `base` transform on /tf.
  std::optional<std::string> odom_topic;
  /// `log_frames.base`: the robot's frame (default: the Odometry's child frame, else base_link).
  std::optional<std::string> base_frame;
  /// `log_frames.odom`: the odometry frame (default: the Odometry's frame, else odom).
  std::optional<std::string> odom_frame;
  /// The manifest's `laser:` overrides of each scan's own settings.
  LaserSettings laser;
  /// What reading the bag may allocate (a chunk's size).
  BagReadLimits limits;
};

/// A bag read as a run, and how it was read.
struct BagLog : RobotLog {
  RobotLogSummary summary;         ///< messages per topic, laser settings used, warnings
  BagContents contents;            ///< every topic the bag holds
  std::string scan_topic;          ///< the topic the scans came from
  std::string odometry_source;     ///< the Odometry topic, or "/tf (odom -> base_link)"
  std::string laser_frame;         ///< the scans' frame
  Pose2 laser_mount;               ///< the laser in the robot's frame, projected to the plane
  bool laser_upside_down = false;  ///< mounted upside down: its beams turn clockwise
};

/// Reads a ROS 1 bag, an MCAP file or a rosbag2 bag (see bag_file.hpp) as a run: scans from the
/// LaserScan topic, each with the robot's odometry pose interpolated at its stamp (from the
/// Odometry topic, else from the odom -> base transforms on /tf) and the laser's mounting pose
/// from base to the scan's frame on /tf_static (and /tf): translation and heading in the plane;
/// a laser mounted upside down (rolled by pi) has its beams reversed. Ranges per REP 117: +inf
/// is no return, -inf too close (read as 0), NaN invalid.
///
/// Scans whose stamp lies outside the odometry's time span are skipped with a warning. A stamp
/// of zero falls back to the time the message was logged.
///
/// Every value used is checked as a CARMEN log's (see bag_message_checks.hpp): a NaN, infinite
/// or absurd odometry pose, velocity, transform or laser setting is refused naming the topic,
/// the message and the field, not read as a number.
///
/// Throws InputError naming the file (and byte offset, for a corrupt container) when the bag
/// holds no LaserScan topic, several where none was chosen, a chosen topic that is missing or
/// of another type, no odometry, a tilted laser, transforms from the base to the laser's frame
/// that loop, a value that is not finite or out of range, or a message that does not decode.
BagLog read_bag_log(const std::filesystem::path& path, const BagLogOptions& options = {});

}  // namespace floorgrid::io
