#include "floorgrid/io/robot_log_reader.hpp"

#include "floorgrid/io/carmen_log.hpp"

namespace floorgrid::io {

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
