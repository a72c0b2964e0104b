#pragma once

#include <optional>
#include <string>
#include <vector>

#include "floorgrid/pipeline/plan_location.hpp"

namespace floorgrid {

/// Why and where the dual check re-initializes the plan filter.
struct PlanRestart {
  std::string reason;   ///< "inconsistent" or "unconverged"
  TrackingStart start;  ///< the new cloud
};

/// The dual check while the plan filter tracks: the plan pose must agree with the gridmap
/// pose through the registration near the robot (a LocalRegistration of the last scans where
/// both filters were sure) or, without one, the global registration. A plan filter that keeps
/// disagreeing, or stays unconverged, is re-initialized where the gridmap filter says.
class DualCheck {
 public:
  /// The check at the plan scale `scale` against `global` (gridmap poses -> plan poses).
  DualCheck(const DualCheckOptions& options, const PlanRegistration& global, double scale);

  /// Judges scan `scan` (the gridmap filter converged on it): sets record.consistent and
  /// returns where to re-initialize the plan filter when it should be.
  std::optional<PlanRestart> judge(std::size_t scan, ScanRecord& record);

  /// The cloud a gridmap filter lost on scan `scan` restarts from when the plan filter is
  /// sure there: around the gridmap pose the registration gives for `plan_pose` (the local
  /// registration when fresh, with its spread, else the global one with its wider spread).
  TrackingStart gridmap_start(std::size_t scan, const Pose2& plan_pose) const;

  /// Forgets the local registration (its poses were of a plan filter found off) and the
  /// disagreements counted.
  void forget_local();

 private:
  const DualCheckOptions& options_;
  const PlanRegistration& global_;
  double scale_;
  LocalRegistration local_;
  int disagreeing_ = 0;  // consecutive scans the plan filter disagreed
  int grossly_ = 0;      // consecutive scans it disagreed grossly
  int unconverged_ = 0;  // consecutive scans the plan filter was not converged
};

/// The gridmap filter's pose on every scan where it was converged (none elsewhere): the plan
/// filter's motion between two such scans (FilterRunner::guide).
std::vector<std::optional<Pose2>> gridmap_guide(const DualLocalization& result);

/// Step 4 of localize_dual: the plan filter tracks the log at `scale` from the plan's start,
/// checked against the gridmap filter scan by scan (DualCheck). Fills every ScanRecord::plan,
/// consistent and plan_reinitialized, and the plan filter's divergences and corrections.
/// Where the gridmap filter was lost while the plan filter is sure (converged on this scan and
/// the one before), a new gridmap filter starts where the plan filter says
/// (DualCheck::gridmap_start) and its records replace the lost ones while it is converged
/// (ScanRecord::grid_mended); it is dropped when it diverges, stays unconverged for
/// DualCheckOptions::mend_scans scans, or the first gridmap filter converges again.
void track_plan(const DualMaps& maps, const RobotLog& log, const DualLocalizerOptions& options,
                const PlanLocation& location, DualLocalization& result,
                const DualProgressCallback& progress);

}  // namespace floorgrid
