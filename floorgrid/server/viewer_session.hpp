#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::server {

/// The robot's latest pose in the grid frame and its number (0: none posted yet): the live feed
/// the viewer follows.
struct RobotPose {
  Pose2 pose_in_grid;
  std::uint64_t sequence = 0;
};

/// What the viewer's API serves, shared by every request thread: the mapping (swapped whole by a
/// refit, so that a request maps every one of its points with one model) and the robot's pose.
class ViewerSession {
 public:
  /// A session answering with `model` (never null); `dataset` names what it came from.
  ViewerSession(std::shared_ptr<const PointMapping> model, std::string dataset);

  /// The mapping now; a request keeps it for all its points, whatever a refit swaps meanwhile.
  std::shared_ptr<const PointMapping> model() const;
  /// Swaps the mapping (never null).
  void set_model(std::shared_ptr<const PointMapping> model);

  /// The latest robot pose posted (sequence 0: none yet).
  RobotPose robot_pose() const;
  /// Posts a robot pose in the grid frame; returns its sequence number.
  std::uint64_t post_robot_pose(const Pose2& pose_in_grid);

  /// What the session came from (the dataset's name).
  const std::string& dataset() const { return dataset_; }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const PointMapping> model_;
  RobotPose robot_;
  std::string dataset_;
};

}  // namespace floorgrid::server
