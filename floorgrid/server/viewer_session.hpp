#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid::server {

/// The robot's latest pose in the grid frame and its number (0: none posted yet): the live feed
/// the viewer follows.
struct RobotPose {
  Pose2 pose_in_grid;
  std::uint64_t sequence = 0;
};

/// A map as the viewer shows it: a PNG (free white, occupied black, unknown grey; top row
/// first) and where its pixels lie in the map's frame.
struct ViewerMap {
  std::string png;        ///< the PNG file's bytes
  GridGeometry geometry;  ///< pixel (ix, iy) is cell (ix, height - 1 - iy)
};

/// A map's picture for the viewer.
ViewerMap viewer_map(const OccupancyGrid& grid);

/// What the viewer's API serves, shared by every request thread: the mapping (swapped whole by a
/// refit, so that a request maps every one of its points with one model) and the robot's pose.
class ViewerSession {
 public:
  /// A session answering with `model` (never null) over the plan and the gridmap; `dataset`
  /// names what it came from.
  ViewerSession(std::shared_ptr<const PointMapping> model, std::string dataset, ViewerMap plan = {},
                ViewerMap grid = {});

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
  /// The plan's picture (empty png: none).
  const ViewerMap& plan() const { return plan_; }
  /// The gridmap's picture (empty png: none).
  const ViewerMap& grid() const { return grid_; }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const PointMapping> model_;
  RobotPose robot_;
  std::string dataset_;
  ViewerMap plan_, grid_;
};

}  // namespace floorgrid::server
