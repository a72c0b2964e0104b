#include "floorgrid/io/dataset/robot_log_reader.hpp"

#include "floorgrid/io/logs/carmen_log.hpp"

namespace floorgrid::io {

BagLogOptions bag_log_options(const DatasetManifest& m) {
  BagLogOptions options;
  options.scan_topic = m.log_scan_topic;
  options.odom_topic = m.log_odom_topic;
  options.base_frame = m.log_base_frame;
  options.odom_frame = m.log_odom_frame;
  options.laser = m.laser;
  return options;
}

ReadRobotLog read_robot_log(const std::filesystem::path& path, const BagLogOptions& options) {
  ReadRobotLog out;
  if (detect_bag_format(path)) {
    BagLog log = read_bag_log(path, options);
    out.summary = std::move(log.summary);
    static_cast<RobotLog&>(out) = std::move(log);
    return out;
  }
  CarmenReadOptions carmen;
  carmen.laser = options.laser;
  CarmenLog log = read_carmen_log(path, carmen);
  out.summary = std::move(log.summary);
  static_cast<RobotLog&>(out) = std::move(log);
  return out;
}

}  // namespace floorgrid::io
