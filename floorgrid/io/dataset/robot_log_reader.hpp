#pragma once

#include <filesystem>

#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/logs/bag_log.hpp"
#include "floorgrid/io/logs/robot_log_summary.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid::io {

/// A run read from any log floorgrid reads, and how it was read.
struct ReadRobotLog : RobotLog {
  RobotLogSummary summary;  ///< counts, settings used, warnings
};

/// The manifest's `log_topics`, `log_frames` and `laser`, as the bag reader takes them.
BagLogOptions bag_log_options(const DatasetManifest& manifest);

/// Reads a ROS 1 bag, an MCAP file or a rosbag2 bag (told by content: read_bag_log with
/// `options`), else a CARMEN log (read_carmen_log with `options.laser`). Throws InputError as
/// those do.
ReadRobotLog read_robot_log(const std::filesystem::path& path, const BagLogOptions& options = {});

}  // namespace floorgrid::io
