#pragma once

#include <filesystem>
#include <vector>

#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid::io {

/// Writes the dual localization's track as CSV (atomically), one row per scan of `log`:
/// `scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,plan_scale,grid_x,
/// grid_y,grid_theta,grid_state,grid_converged,grid_fit,grid_scale,consistent,pairs`. Poses are
/// each filter's mean after the scan (plan metres, grid metres, radians), states FilterState's
/// names, the fits the mean beam likelihood at the last update's estimate (empty where the map
/// could not tell), the scales that estimate's (world metres per map metre), `consistent`
/// whether the plan pose agreed with the gridmap pose, `pairs` the pairs the scan made. Where a
/// filter stood on each scan: what an operator looks at when the converged share is low.
void write_scans_csv(const DualLocalization& localization, const RobotLog& log,
                     const std::filesystem::path& path);

/// A gridmap pose of the run at a time: what `serve --replay` feeds as the live pose.
struct TimedPose {
  double time = 0.0;  ///< the scan's timestamp, seconds (NaN where the log had none)
  Pose2 pose_in_grid;
};

/// The gridmap filter's track from a scans.csv (columns found by the header: time, grid_x,
/// grid_y, grid_theta, grid_state), the scans where it was tracking. InputError naming the file
/// and line on a missing column or a bad number.
std::vector<TimedPose> read_grid_track(const std::filesystem::path& path);

}  // namespace floorgrid::io
