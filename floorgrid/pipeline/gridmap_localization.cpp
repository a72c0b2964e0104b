#include "floorgrid/pipeline/gridmap_localization.hpp"

#include <algorithm>
#include <chrono>
#include <string>

namespace floorgrid {

namespace {

/// The gridmap filter at its start: a cloud around the given start, or the best hypotheses
/// for the first scan over the whole map.
ParticleFilter start_gridmap_filter(const DualMaps& maps, const std::optional<StartPoses>& start,
                                    const DualLocalizerOptions& options) {
  ParticleFilter filter(options.grid.filter, stream_seed(options.seed, SeedStream::gridmap_filter));
  if (start) {
    filter.initialize_tracking(TrackingStart{.pose = start->grid}, maps.gridmap());
  } else {
    filter.initialize_from_hypotheses(maps.gridmap(), maps.grid_observation(0),
                                      maps.grid_model().field(), std::nullopt, options.threads);
  }
  return filter;
}

/// Lost on the gridmap at scan `i`: localize globally again from this scan's best hypotheses
/// (far more reliable than waiting for the recovery's injected particles to find the place).
void reseed_globally(FilterRunner& runner, const DualMaps& maps, std::size_t i,
                     const DualLocalizerOptions& options) {
  runner.filter() =
      ParticleFilter(options.grid.filter, stream_seed(options.seed, SeedStream::gridmap_reseed, i));
  runner.filter().initialize_from_hypotheses(maps.gridmap(), maps.grid_observation(i),
                                             maps.grid_model().field(), std::nullopt,
                                             options.threads);
}

/// The filter's last converged pose.
struct LastConverged {
  std::size_t scan = 0;
  Pose2 pose;
};

/// Lost on the gridmap at scan `i` after converging: restart as a wide cloud around the last
/// converged pose carried on to scan `i` by the odometry (the estimate of a diverging filter
/// may already be a corridor off or turned around), wider the farther the robot went since.
void reseed_near(FilterRunner& runner, const DualMaps& maps, const RobotLog& log,
                 const LastConverged& last, std::size_t i, const DualLocalizerOptions& options) {
  const GridmapLocalizationOptions& o = options.gridmap_localization;
  const Pose2 moved = log.scans[last.scan].robot_pose.between(log.scans[i].robot_pose);
  const double travelled = moved.translation().norm();
  runner.filter() =
      ParticleFilter(options.grid.filter, stream_seed(options.seed, SeedStream::gridmap_reseed, i));
  runner.filter().initialize_tracking(
      TrackingStart{.pose = last.pose.compose(moved),
                    .position_sigma = o.restart_sigma * (1.0 + 0.1 * travelled),
                    .heading_sigma = o.restart_heading_sigma},
      maps.gridmap());
}

/// Why the gridmap filter did not converge, and what to check.
LocalizationStatus not_converged(const DualLocalizerInputs& inputs, int scans) {
  LocalizationStatus status{.ok = false, .message = {}, .field = "gridmap"};
  status.message = "the gridmap filter did not converge within " + std::to_string(scans) + " scans";
  if (inputs.start) {
    status.message +=
        ", neither from the given initial_pose.grid nor by global localization: check "
        "initial_pose.grid, the gridmap's resolution and origin, and the log's laser settings";
    status.field = "initial_pose";
  } else {
    status.message +=
        " of global localization: check the gridmap's resolution and origin and the log's "
        "laser settings, or give initial_pose";
  }
  return status;
}

}  // namespace

GridmapLocalization localize_on_gridmap(const DualMaps& maps, const DualLocalizerInputs& inputs,
                                        const DualLocalizerOptions& options,
                                        DualLocalization& result,
                                        const DualProgressCallback& progress) {
  const auto clock = std::chrono::steady_clock::now();
  const std::size_t n = inputs.log.scans.size();
  const std::size_t max_global_scans =
      static_cast<std::size_t>(std::max(1, options.gridmap_localization.max_global_scans));
  bool start_held = inputs.start.has_value();  // did the filter keep to the given start?
  FilterRunner runner(start_gridmap_filter(maps, inputs.start, options), maps.grid_model().model(),
                      maps.grid_walls(), inputs.log, maps.grid_observation_options(),
                      options.grid.runner);
  if (!inputs.start)
    runner.start_at(0);  // the hypotheses used scan 0
  GridmapLocalization found;
  const auto near_scans =
      static_cast<std::size_t>(std::max(0, options.gridmap_localization.restart_near_scans));
  std::optional<LastConverged> last;   // since the last restart
  std::optional<std::size_t> near_at;  // the scan of a restart near `last` not yet converged
  for (std::size_t i = inputs.start ? 0 : 1; i < n; ++i) {
    FilterRecord& r = result.scans[i].grid = runner.step(i);
    if (r.converged) {
      last = LastConverged{i, r.pose};
      near_at.reset();
    }
    const bool near_failed = near_at && i >= *near_at + near_scans;
    if (r.diverged || near_failed) {
      if (r.diverged) {
        count_divergence(result.grid_divergences,
                         std::string(to_string(runner.filter().status().divergence.reason)));
      }
      start_held = start_held && found.first_converged.has_value();
      // Once converged, the robot is near where the filter last was: look there first, and
      // over the whole map only when that does not converge.
      result.grid_restarts.near_failed += near_failed;
      if (last && near_scans > 0) {
        ++result.grid_restarts.near;
        reseed_near(runner, maps, inputs.log, *last, i, options);
        near_at = i;
        r.state = FilterState::tracking;
      } else {
        ++result.grid_restarts.global;
        reseed_globally(runner, maps, i, options);
        near_at.reset();
        r.state = FilterState::global;
      }
      last.reset();
      r.converged = false;
    }
    if (r.converged && !found.first_converged) {
      found.first_converged = i;
      if (!inputs.start)
        result.global_localization_seconds = seconds_since(clock);
    }
    if (!found.first_converged && i >= max_global_scans) {
      result.status = not_converged(inputs, options.gridmap_localization.max_global_scans);
      return found;
    }
    report_progress(progress, "gridmap", i + 1, n, r.converged);
  }
  if (!found.first_converged) {
    result.status = not_converged(inputs, static_cast<int>(n));
    return found;
  }
  result.grid_start_scan = *found.first_converged;
  result.grid_corrections = runner.corrections();
  result.tracking_evaluations += runner.evaluations();
  // A given start the gridmap filter had to abandon says nothing about the plan either: the
  // plan is then located like without a start.
  if (inputs.start && !start_held) {
    result.notes.push_back(
        "the gridmap filter diverged from the given start before converging: "
        "initial_pose ignored, the plan located by registering the run");
  }
  found.start = start_held ? inputs.start : std::nullopt;
  return found;
}

}  // namespace floorgrid
