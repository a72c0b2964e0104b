#include "floorgrid/server/viewer_session.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/mapping/fit_with_uncertainty.hpp"

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
  ++model_version_;
}

std::uint64_t ViewerSession::model_version() const {
  const std::lock_guard lock(mutex_);
  return model_version_;
}

VersionedLayers ViewerSession::layers() {
  if (!renderer_)
    return {model_version(), model()->name(), nullptr};
  const std::lock_guard drawing(layers_mutex_);
  std::shared_ptr<const PointMapping> model;
  std::uint64_t version = 0;
  {
    const std::lock_guard lock(mutex_);
    model = model_;
    version = model_version_;
  }
  if (!layers_.layers || layers_.model_version != version)
    layers_ = {version, model->name(), std::make_shared<const ModelLayers>(renderer_(*model))};
  return layers_;
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

std::vector<ManualPair> ViewerSession::manual_pairs() const {
  const std::lock_guard lock(mutex_);
  return manual_;
}

std::uint64_t ViewerSession::add_pair(const Eigen::Vector2d& point_in_plan,
                                      const Eigen::Vector2d& point_in_grid) {
  const std::lock_guard lock(mutex_);
  manual_.push_back({next_pair_id_, point_in_plan, point_in_grid});
  return next_pair_id_++;
}

PairBounds ViewerSession::pair_bounds() const {
  PairBounds bounds;
  if (!plan_.png.empty())
    bounds.plan = plan_.geometry.bounds();
  if (!grid_.png.empty())
    bounds.grid = grid_.geometry.bounds();
  return bounds;
}

bool ViewerSession::delete_pair(std::uint64_t id) {
  const std::lock_guard lock(mutex_);
  const auto it = std::find_if(manual_.begin(), manual_.end(),
                               [id](const ManualPair& p) { return p.id == id; });
  if (it == manual_.end())
    return false;
  manual_.erase(it);
  return true;
}

RefitSummary ViewerSession::refit(const MappingOptions& options) {
  const std::lock_guard refitting(refit_mutex_);
  const std::vector<ManualPair> manual = manual_pairs();
  // Named by the id the operator sees, not by the index the fit would name.
  for (const ManualPair& p : manual) {
    const Eigen::Vector4d both(p.point_in_plan.x(), p.point_in_plan.y(), p.point_in_grid.x(),
                               p.point_in_grid.y());
    if (!(both.allFinite() && both.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      throw InputError("manual pair " + std::to_string(p.id) +
                           " has a coordinate that is not finite or lies farther than 1e7 m "
                           "from the origin: delete it",
                       {}, 0, "pairs");
    }
  }
  ReferencePairs pairs;
  const Eigen::Index base = base_pairs_.size();
  const auto n = base + static_cast<Eigen::Index>(manual.size());
  pairs.points_in_plan.resize(2, n);
  pairs.points_in_grid.resize(2, n);
  if (base > 0) {
    pairs.points_in_plan.leftCols(base) = base_pairs_.points_in_plan;
    pairs.points_in_grid.leftCols(base) = base_pairs_.points_in_grid;
  }
  for (std::size_t i = 0; i < manual.size(); ++i) {
    pairs.points_in_plan.col(base + static_cast<Eigen::Index>(i)) = manual[i].point_in_plan;
    pairs.points_in_grid.col(base + static_cast<Eigen::Index>(i)) = manual[i].point_in_grid;
  }
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<PointMapping> model = make_mapping(options);
  // As align and fit make it: with its cross-validated error and its std_m.
  fit_with_uncertainty(*model, options, pairs, options.auto_select.cv);
  RefitSummary summary;
  summary.model = model->name();
  summary.pairs = static_cast<std::size_t>(n);
  summary.rms_m = model->summary().rms_m;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.cv_error_m = model->summary().cv_error_m;
  summary.has_std = model->error_model().has_value();
  set_model(std::move(model));
  return summary;
}

}  // namespace floorgrid::server
