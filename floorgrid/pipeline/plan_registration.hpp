#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/localization/particle_initialization.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_alignment.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// How the laser endpoints of many scans become one point cloud (a submap).
struct SubmapOptions {
  double bin = 0.2;               ///< metres: one point per bin of this size (> 0)
  std::size_t max_points = 6000;  ///< at most this many points, evenly thinned (>= 1)
  double max_range = 15.0;        ///< metres: longer readings are left out
};

/// The endpoints of `scans` (indices into `log`), each seen from its pose in `poses` (a map
/// frame in world metres, e.g. the gridmap's), gathered in the frame of `origin` (also in that
/// map) as one ScanObservation: what a robot at `origin` with an unlimited laser would see.
ScanObservation build_submap(const RobotLog& log, std::span<const std::size_t> scans,
                             std::span<const Pose2> poses, const Pose2& origin,
                             const SubmapOptions& options = {});

/// At most `points` of `cloud` (at least one), evenly thinned.
ScanObservation thin(const ScanObservation& cloud, std::size_t points);

/// How a run is located on a plan.
struct PlanRegistrationOptions {
  /// The lattice: 0.25 m, 7.5 degrees, ten scales; coarse enough to be quick, fine enough for
  /// the plan filter (started with a metre and 0.2 rad of spread) to settle from.
  HypothesisSeedingOptions seeding{.position_step = 0.25,
                                   .headings = 48,
                                   .scales = 10,
                                   .keep = 256,
                                   .max_hypotheses = 6'000'000,
                                   .jitter = false};
  /// The lattice is scored with this many of the submap's points (evenly thinned); its best
  /// `seeding.keep` are then rescored with every point, each refined over a 3 x 3 x 3 x 3
  /// sub-lattice of half steps, and the best wins.
  std::size_t coarse_points = 1500;
  /// The runner-up is the best hypothesis farther than this (metres) or turned more than
  /// runner_up_heading (radians) from the best: how clearly the best won.
  double runner_up_distance = 2.0;
  double runner_up_heading = 0.5;  ///< radians
  double min_scale = 1e-3;         ///< refined scales are kept above this
  std::uint64_t seed = 1;          ///< randomness of the lattice's seeding
};

/// Where a run lies on a plan: the plan pose and scale of one robot pose of the run, so that
/// every pose of the run (in the map it was localized in, world metres) has a plan pose.
class PlanRegistration {
 public:
  PlanRegistration() = default;
  /// The registration in which `origin_in_map` lies at `origin_in_plan`, the plan's metre being
  /// `scale` world metres.
  PlanRegistration(const Pose2& origin_in_map, const Pose2& origin_in_plan, double scale)
      : origin_in_map_(origin_in_map), origin_in_plan_(origin_in_plan), scale_(scale) {}
  /// The registration the maps' bent alignment gives: every pose mapped through `warp`
  /// (gridmap -> plan, not one similarity), `scale` world metres per plan metre its global scale.
  PlanRegistration(std::shared_ptr<const MapWarp> warp, double scale)
      : scale_(scale), warp_(std::move(warp)) {}

  /// The plan pose of a pose in the map (world metres).
  Pose2 plan_pose(const Pose2& pose_in_map) const;
  /// The map pose of a plan pose: the inverse of plan_pose.
  Pose2 map_pose(const Pose2& pose_in_plan) const;
  /// World metres per plan metre.
  double scale() const { return scale_; }
  /// The maps' warp it maps through, or null (one similarity).
  const MapWarp* warp() const { return warp_.get(); }
  /// The registered robot pose in the map.
  const Pose2& origin_in_map() const { return origin_in_map_; }
  /// And its plan pose.
  const Pose2& origin_in_plan() const { return origin_in_plan_; }

 private:
  Pose2 origin_in_map_;
  Pose2 origin_in_plan_;
  double scale_ = 1.0;
  std::shared_ptr<const MapWarp> warp_;
};

/// The registration near the robot, from the poses of the last scans where both filters were
/// sure (matched on both maps and consistent): the mean heading offset and the centroids of
/// the positions give a rigid map at the plan's scale that follows a plan drawn slightly wrong
/// or a gridmap bent by SLAM drift, as a global registration cannot.
class LocalRegistration {
 public:
  /// Keeps the last `window` pose pairs (>= 1); `scale` is world metres per plan metre.
  LocalRegistration(std::size_t window, double scale) : window_(window), scale_(scale) {}

  /// Adds the poses of scan `scan` in both maps (the oldest pair leaves a full window).
  void add(std::size_t scan, const Pose2& pose_in_map, const Pose2& pose_in_plan);
  /// Whether at least `min_pairs` pairs are held and the newest is at most `max_age` scans
  /// older than `scan`.
  bool fresh(std::size_t scan, std::size_t min_pairs, std::size_t max_age) const;
  /// The plan pose of a map pose by the current local registration (fresh() must hold).
  Pose2 plan_pose(const Pose2& pose_in_map) const;
  /// The map pose of a plan pose: the inverse of plan_pose.
  Pose2 map_pose(const Pose2& pose_in_plan) const;
  /// Map metres from `pose_in_map` to the nearest map pose held (infinity when none): how far
  /// the registration is carried beyond where it was fitted.
  double distance_to(const Pose2& pose_in_map) const;
  /// Forgets every pair.
  void clear();

 private:
  struct Pair {
    std::size_t scan;
    Pose2 map, plan;
  };
  void refit();

  std::size_t window_;
  double scale_;
  std::vector<Pair> pairs_;  // a ring of at most window_ pairs
  std::size_t next_ = 0;
  Pose2 offset_;  // plan pose of the map frame's origin (rotation, translation)
};

/// The registration found by register_on_plan, with how clearly it won.
struct PlanRegistrationResult {
  PlanRegistration registration;  ///< the best hypothesis
  double log_likelihood = 0.0;    ///< its score
  /// Score of the best hypothesis more than 2 m or 0.5 rad from the best (none: 0).
  double runner_up_log_likelihood = 0.0;
  std::size_t hypotheses = 0;  ///< scored
  std::size_t points = 0;      ///< of the submap
};

/// Global localization of a submap on the plan: every pose of a lattice over the plan's free
/// space x headings (x scales over `scales` when the plan's scale is unknown, else `scale`) is
/// scored with `model` (the plan's likelihood field) on a thinned submap, and the best few are
/// rescored and refined with the whole submap. A submap spanning a
/// long stretch of the run is far less ambiguous than one scan (a corridor of identical doors
/// has one place where a whole tour fits). O(hypotheses x points) in `threads` threads.
PlanRegistrationResult register_on_plan(const OccupancyGrid& plan, const ObservationModel& model,
                                        const ScanObservation& submap, const Pose2& submap_origin,
                                        const std::optional<ScaleRange>& scales, double scale,
                                        const PlanRegistrationOptions& options,
                                        int threads = kDefaultThreads);

}  // namespace floorgrid
