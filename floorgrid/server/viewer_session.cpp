#include "floorgrid/server/viewer_session.hpp"

#include <stdexcept>
#include <utility>

#include "floorgrid/io/image_io.hpp"
#include "floorgrid/io/map_io.hpp"

namespace floorgrid::server {

ViewerMap viewer_map(const OccupancyGrid& grid) {
  const std::vector<std::uint8_t> grey = io::grid_to_image(grid, io::MapMetadata{}, nullptr);
  return {io::encode_png(grid.width(), grid.height(), 1, grey), grid.geometry()};
}

ViewerSession::ViewerSession(std::shared_ptr<const PointMapping> model, std::string dataset,
                             ViewerMap plan, ViewerMap grid)
    : dataset_(std::move(dataset)), plan_(std::move(plan)), grid_(std::move(grid)) {
  set_model(std::move(model));
}

std::shared_ptr<const PointMapping> ViewerSession::model() const {
  const std::lock_guard lock(mutex_);
  return model_;
}

void ViewerSession::set_model(std::shared_ptr<const PointMapping> model) {
  if (!model)
    throw std::invalid_argument("ViewerSession: a null model");
  const std::lock_guard lock(mutex_);
  model_ = std::move(model);
}

RobotPose ViewerSession::robot_pose() const {
  const std::lock_guard lock(mutex_);
  return robot_;
}

std::uint64_t ViewerSession::post_robot_pose(const Pose2& pose_in_grid) {
  const std::lock_guard lock(mutex_);
  robot_.pose_in_grid = pose_in_grid;
  return ++robot_.sequence;
}

}  // namespace floorgrid::server
