#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// How the plan poses' pull along the robot's heading is measured from the run and taken out
/// of the pairs (DualLocalizerOptions::pose_pull).
///
/// A 180-degree laser sees the walls ahead and beside the robot, never behind. Whatever makes
/// the walls ahead lie deeper in one map than the laser measures (walls built thicker than
/// drawn, furniture a drawing lacks, a wall met half a cell off its face) moves that map's
/// matched pose forward, and the pairs of a place driven in one direction keep it. Two visits
/// of one place facing opposite ways show it without any truth: their plan poses differ, less
/// what their gridmap poses differ through the pairs' similarity, by the pull forward of the
/// one minus the pull forward of the other.
struct PosePullOptions {
  bool enabled = true;  ///< measure the pull and, when it is measured well, take it out
  /// World metres: two scans whose gridmap poses lie this close are at one place.
  double radius = 1.0;
  /// Radians: ... and their headings differ by at least this much (90 degrees: one was
  /// driven back the way the other came, or turned).
  double min_turn = 1.5707963267948966;
  /// Seconds: ... and they are at least this far apart in time (a later visit, not the next
  /// scan of the same pass, whose errors the filters share).
  double min_time_apart = 5.0;
  /// Scans with a comparison needed before the pull is used.
  std::size_t min_scans = 100;
  /// World metres: the pull is used only when its standard error is at most this...
  double max_std = 0.02;
  /// ... and it is at most this large (larger is a filter off by more than a pull).
  double max_pull = 0.25;
};

/// The pull measured (DualLocalization::pose_pull).
struct PosePull {
  /// World metres: how far the plan pose stands ahead of the gridmap's along the robot's
  /// heading, less what the pairs' similarity explains (the median over the scans of each
  /// scan's median comparison).
  double along_m = 0.0;
  /// World metres: its standard error, from the spread of ten blocks of scans in time.
  double std_m = 0.0;
  std::size_t scans = 0;        ///< scans with at least one comparison
  std::size_t comparisons = 0;  ///< pairs of visits compared
  bool applied = false;         ///< whether the pairs were made with it taken out
};

/// One scan's poses in both maps, as the pairs are made from them.
struct PullSample {
  double time = 0.0;   ///< seconds
  Pose2 pose_in_plan;  ///< plan metres
  Pose2 pose_in_grid;  ///< grid metres
};

/// The pull of the plan poses against the gridmap poses over `samples` (in time order),
/// `plan_scale` world metres per plan metre; nullopt when no two visits could be compared.
/// `applied` is set when it passes the options' gates.
std::optional<PosePull> measure_pose_pull(const std::vector<PullSample>& samples, double plan_scale,
                                          const PosePullOptions& options);

/// `pose_in_plan` moved back along its heading by `pull_m` world metres (`plan_scale` world
/// metres per plan metre): the pose with the pull taken out.
Pose2 without_pull(const Pose2& pose_in_plan, double pull_m, double plan_scale);

}  // namespace floorgrid
