#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/pipeline/plan_registration.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// The submap check while the plan filter tracks: the laser endpoints of the last scans, seen
/// from the gridmap filter's sure poses, are one rigid submap; placed on the plan where the
/// plan filter says the robot is, it must fit there at least as well as anywhere near. One
/// scan at a time, a plan filter in a building of look-alike offices and long corridors can
/// settle a door or a few metres off and follow the run from there, and the dual check's
/// local registration, fitted on its own last poses, follows it (fr079's real log: the first
/// 100-500 scans 1.6-2.7 m off on 8 of 10 seeds, and 1,600-2,000 scans 1.5-4 m off on 2). A
/// submap spanning metres of the run has one place where it fits.
///
/// Off by default: on fr079's real log it keeps every seed's pairs on the hand-made pairs, but
/// on simulated architects' drawings (doors and partitions drawn where they are not) it also
/// re-places filters that were right, and local models (tps, gp) fitted to those stretches'
/// pairs got worse on a third of the rows (README, "The submap check").
struct SubmapCheckOptions {
  bool enabled = false;
  std::size_t every = 20;    ///< scans between two checks
  std::size_t window = 200;  ///< scans back the submap may reach
  /// A scan joins the submap when the gridmap pose moved this far (world metres) or turned
  /// `spacing_heading` since the last one that joined...
  double spacing = 0.1;
  double spacing_heading = 0.1;  ///< radians
  std::size_t max_scans = 40;    ///< ... and at most this many (the newest) make the submap
  std::size_t min_scans = 10;    ///< fewer: no check
  /// The submap's points (world metres): one per bin, at most max_points.
  SubmapOptions submap{.bin = 0.1, .max_points = 1500, .max_range = 10.0};
  /// The search around the plan filter's pose: shifts up to this far each way (world metres)
  /// on a lattice of `search_step`, turns up to `search_heading` each way in `heading_step`
  /// steps (about the robot), scored with `coarse_points` of the submap's points; the best
  /// near the plan filter's pose and the best away from it are refined with all of them.
  double search_distance = 2.5;
  double search_step = 0.2;
  double search_heading = 0.1;  ///< radians
  double heading_step = 0.05;   ///< radians
  std::size_t coarse_points = 400;
  /// The plan filter is re-initialized at the best placement at least this far (world metres)
  /// from its pose when that placement explains at least `min_gain` more of the submap
  /// (ObservationModel::mean_beam_likelihood, a share in [0, 1]) than the best nearer.
  double min_shift = 0.75;
  double min_gain = 0.05;
  /// World metres: a placement farther than this from where the run's global registration
  /// (the maps' bent alignment, or the similarity the run was located by) puts the robot is
  /// not taken. A drawing's corridor of doors drawn a metre or two off fits a submap shifted by
  /// a door's pitch (fr079's real log, seeds 1-10, judged against its hand-made pairs: without
  /// this limit 82 of 153 re-placements moved the plan filter away from them; with it, 27 of
  /// 119).
  double max_from_registration = 2.0;
  /// Checks in a row that must find the better placement (the same shift within min_shift)
  /// before the plan filter is re-placed: a filter truly off stays off, while a submap that
  /// fits a misdrawn stretch better elsewhere seldom does twice.
  std::size_t confirmations = 1;
};

/// Where a check places the plan filter instead.
struct SubmapRelocation {
  Pose2 plan_pose;            ///< the better placement of the robot (plan frame)
  double shift = 0.0;         ///< world metres from the plan filter's pose
  double share_before = 0.0;  ///< the submap's explained share at the best placement near it
  double share_after = 0.0;   ///< and at the better placement
};

/// Gathers the gridmap filter's sure poses of a run and checks the plan filter against them.
class SubmapCheck {
 public:
  /// `plan_field` is the plan's likelihood field (plan metres); `scale` world metres per plan
  /// metre. Everything referenced must outlive the check.
  SubmapCheck(const SubmapCheckOptions& options, const RobotLog& log,
              const ObservationModel& plan_field, double scale);

  /// Scan `scan`, where the gridmap filter was sure at `grid_pose`: it joins the submap when
  /// the robot moved enough since the last scan that joined.
  void add(std::size_t scan, const Pose2& grid_pose);
  /// Whether scan `scan` is due for a check (every `every` scans, with a new scan joined).
  bool due(std::size_t scan) const;
  /// Checks the plan filter's pose `plan_pose` on scan `scan` (the gridmap filter's at
  /// `grid_pose`; `registered` the plan pose the global registration gives it): a placement of
  /// the submap at least min_shift away, within max_from_registration of `registered`, that
  /// explains min_gain more of it, once `confirmations` checks in a row found it; or none.
  std::optional<SubmapRelocation> check(std::size_t scan, const Pose2& grid_pose,
                                        const Pose2& plan_pose, const Pose2& registered);

 private:
  /// One check's search, without the confirmations.
  std::optional<SubmapRelocation> search(const Pose2& grid_pose, const Pose2& plan_pose,
                                         const Pose2& registered) const;
  struct Joined {
    std::size_t scan;
    Pose2 pose;
  };
  const SubmapCheckOptions& options_;
  const RobotLog& log_;
  const ObservationModel& field_;
  double scale_;
  std::deque<Joined> joined_;
  std::optional<std::size_t> last_check_;
  std::optional<Eigen::Vector2d> pending_;  // plan metres: the shift the last checks found
  std::size_t confirmed_ = 0;               // checks in a row that found it
  std::size_t joined_since_check_ = 0;
};

}  // namespace floorgrid
