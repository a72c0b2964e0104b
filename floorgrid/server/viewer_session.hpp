#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/server/map_request.hpp"
#include "floorgrid/server/viewer_layers.hpp"

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

/// A pair the operator added by hand (metres), with its number.
struct ManualPair {
  std::uint64_t id = 0;
  Eigen::Vector2d point_in_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d point_in_grid = Eigen::Vector2d::Zero();
};

/// What a refit did.
struct RefitSummary {
  std::string model;      ///< the model fitted
  std::size_t pairs = 0;  ///< pairs it was fitted to (the alignment's and the manual ones)
  double rms_m = 0.0;     ///< its rms residual at them
  double seconds = 0.0;   ///< how long the fit took (with its cross-validation)
  std::optional<double> cv_error_m;  ///< its cross-validated mean error (none: too few pairs)
  bool has_std = false;              ///< whether it states std_m (an error model was fitted)
};

/// A model's layers and the model version they were drawn for.
struct VersionedLayers {
  std::uint64_t model_version = 0;
  std::string model;                          ///< that model's name
  std::shared_ptr<const ModelLayers> layers;  ///< null: the session draws no layers
};

/// A run replayed as the live pose (`serve --replay`).
struct ReplayInfo {
  std::size_t poses = 0;  ///< poses in one pass
  double speed = 1.0;     ///< times real time
};

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
  /// The mapping's number: 1 for the first, one more at each swap (the page's cache key).
  std::uint64_t model_version() const;

  /// Sets what draws the layers (before serving; none: the session has no layers).
  void set_layer_renderer(LayerRenderer renderer) { renderer_ = std::move(renderer); }
  /// Whether the session draws layers.
  bool has_layers() const { return static_cast<bool>(renderer_); }
  /// The current model's layers, drawn on the first call after each swap (one drawing at a time;
  /// the callers meanwhile wait for it rather than draw twice).
  VersionedLayers layers();

  /// The replay feeding the live pose, if any.
  const std::optional<ReplayInfo>& replay() const { return replay_; }
  /// Says that a replay feeds the live pose (before serving).
  void set_replay(ReplayInfo replay) { replay_ = replay; }

  /// The latest robot pose posted (sequence 0: none yet).
  RobotPose robot_pose() const;
  /// Posts a robot pose in the grid frame; returns its sequence number.
  std::uint64_t post_robot_pose(const Pose2& pose_in_grid);

  /// The alignment's pairs the session started from (never edited).
  const ReferencePairs& base_pairs() const { return base_pairs_; }
  /// Sets the alignment's pairs (before serving).
  void set_base_pairs(ReferencePairs pairs) { base_pairs_ = std::move(pairs); }
  /// The manual pairs, in the order they were added.
  std::vector<ManualPair> manual_pairs() const;
  /// Adds a manual pair; returns its number.
  std::uint64_t add_pair(const Eigen::Vector2d& point_in_plan,
                         const Eigen::Vector2d& point_in_grid);
  /// Where manual pairs may lie (check_pair_near_maps): the plan's and the gridmap's bounds,
  /// none for a map the session lacks.
  PairBounds pair_bounds() const;
  /// Deletes manual pair `id`; false when there is none.
  bool delete_pair(std::uint64_t id);
  /// Fits `options.model` to the alignment's and the manual pairs, with its cross-validated
  /// error and std_m (options.auto_select.cv's folds), and swaps it in when the fit succeeds (one
  /// refit at a time; requests meanwhile map with the model before). InputError from the fit (too
  /// few pairs, an unknown model, a manual pair beyond kMaxCoordinate, named by its id) leaves the
  /// model as it was.
  RefitSummary refit(const MappingOptions& options);

  /// What the session came from (the dataset's name).
  const std::string& dataset() const { return dataset_; }
  /// The plan's picture (empty png: none).
  const ViewerMap& plan() const { return plan_; }
  /// The gridmap's picture (empty png: none).
  const ViewerMap& grid() const { return grid_; }

 private:
  mutable std::mutex mutex_;
  std::mutex refit_mutex_;  ///< one refit at a time
  ReferencePairs base_pairs_;
  std::vector<ManualPair> manual_;
  std::uint64_t next_pair_id_ = 1;
  std::shared_ptr<const PointMapping> model_;
  std::uint64_t model_version_ = 0;
  LayerRenderer renderer_;
  std::mutex layers_mutex_;  ///< one drawing at a time
  VersionedLayers layers_;   ///< the last drawn (guarded by layers_mutex_)
  std::optional<ReplayInfo> replay_;
  RobotPose robot_;
  std::string dataset_;
  ViewerMap plan_, grid_;
};

}  // namespace floorgrid::server
