#include "floorgrid/pipeline/plan_scale_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

namespace floorgrid {

namespace {

/// A scale and its spread.
struct ScaleEstimate {
  double scale = 1.0;
  double std = 0.0;
};

/// What the plan filter's scale search saw.
struct ScaleTrack {
  ScaleEstimate estimate;                            ///< over the window's second half
  std::vector<std::pair<std::size_t, Pose2>> poses;  ///< (scan, pose) where it was converged
};

/// The plan filter of the search: particles with scales spread around the registration's.
FilterRunner scale_search_runner(const DualMaps& maps, const RobotLog& log,
                                 const ObservationModel& model,
                                 const std::vector<ScanObservation>& observations,
                                 const DualLocalizerOptions& options, const PlanLocation& location,
                                 const Pose2& start) {
  ParticleFilterOptions filter_options = options.plan.filter;
  filter_options.scale_walk = options.scale_search.walk;
  ParticleFilter filter(filter_options, stream_seed(options.seed, SeedStream::scale_search));
  filter.initialize_tracking(plan_start(start, location.start_sigma, location.start_heading_sigma,
                                        location.scale, location.scale_sigma),
                             maps.plan());
  FilterRunnerOptions runner = options.plan.runner;
  runner.improved_proposal = false;  // the proposal would match at the mean scale
  runner.refine = false;
  return FilterRunner(std::move(filter), model, maps.plan_walls(), log, observations, runner);
}

/// The mean of the estimates, with a spread that adds their mean variance and their scatter.
ScaleEstimate pool(const std::vector<double>& means, const std::vector<double>& variances) {
  double mean = 0.0, within = 0.0, between = 0.0;
  for (std::size_t j = 0; j < means.size(); ++j) {
    mean += means[j];
    within += variances[j];
  }
  mean /= static_cast<double>(means.size());
  within /= static_cast<double>(means.size());
  for (const double m : means)
    between += (m - mean) * (m - mean);
  between /= static_cast<double>(means.size());
  return {mean, std::sqrt(within + between)};
}

/// The filter tracks `scans` scans from `first`; the scale is pooled over the converged scans
/// of the window's second half (or taken from the last scan when it never converged).
ScaleTrack track_scale(FilterRunner& runner, std::size_t first, std::size_t scans, std::size_t n,
                       std::vector<std::string>& notes) {
  ScaleTrack track;
  std::vector<double> means, variances;
  const std::size_t end = std::min(n, first + scans);
  for (std::size_t i = first; i < end; ++i) {
    const FilterRecord r = runner.step(i);
    if (r.converged)
      track.poses.emplace_back(i, r.pose);
    if (i >= first + (end - first) / 2 && r.converged) {
      means.push_back(r.estimate.scale);
      variances.push_back(r.estimate.scale_std * r.estimate.scale_std);
    }
  }
  if (means.empty()) {
    const PoseEstimate last = estimate_pose(runner.filter().particles());
    means.push_back(last.scale);
    variances.push_back(last.scale_std * last.scale_std);
    notes.push_back(
        "the plan filter did not converge during the scale search: scale from its last scan");
  }
  track.estimate = pool(means, variances);
  return track;
}

/// The profile: of scales around `scale`, the one that puts the most endpoints of (up to
/// profile_scans of) the tracked scans exactly on the plan's walls.
double profile_search(const DualMaps& maps, const RobotLog& log,
                      const DualLocalizerOptions& options, const ScaleTrack& track, double scale) {
  const ScaleSearchOptions& search = options.scale_search;
  const std::size_t count =
      std::min(track.poses.size(), std::max<std::size_t>(1, search.profile_scans));
  std::vector<ScanObservation> points;
  std::vector<Pose2> poses;
  for (std::size_t k = 0; k < count; ++k) {
    const auto& [scan, pose] = track.poses[k * track.poses.size() / count];
    points.push_back(make_observation(log.scans[scan], options.plan.runner.match_observation));
    poses.push_back(pose);
  }
  std::vector<const ScanObservation*> views;
  for (const ScanObservation& p : points)
    views.push_back(&p);
  std::vector<double> candidates;
  for (int k = -search.profile_steps; k <= search.profile_steps; ++k)
    candidates.push_back(scale * (1.0 + search.profile_range * k / search.profile_steps));
  return profile_scale(maps.plan_walls(), views, poses, candidates, options.plan.runner.match,
                       maps.plan_rays(), options.plan.runner.beam_tolerance)
      .best;
}

}  // namespace

void search_plan_scale(const DualMaps& maps, const RobotLog& log,
                       const DualLocalizerOptions& options, PlanLocation& location,
                       DualLocalization& result) {
  const auto clock = std::chrono::steady_clock::now();
  const ScaleSearchOptions& search = options.scale_search;
  const MapModel model(maps.plan(), options.plan.likelihood, search.model, options.beam);
  const std::vector<ScanObservation> observations = prepare_observations(log, search.observation);
  FilterRunner runner = scale_search_runner(maps, log, model.model(), observations, options,
                                            location, result.start.plan);
  const ScaleTrack track = track_scale(runner, result.plan_start_scan,
                                       static_cast<std::size_t>(std::max(1, search.scans)),
                                       log.scans.size(), result.notes);
  double scale = track.estimate.scale;
  result.plan_scale_std = track.estimate.std;
  if (!track.poses.empty() && search.profile_steps > 0) {
    const double profiled = profile_search(maps, log, options, track, scale);
    if (std::abs(profiled / scale - 1.0) > 1e-9)
      result.notes.push_back("the scale search gave " + std::to_string(scale) +
                             ", the profile of matched scans " + std::to_string(profiled));
    scale = profiled;
  }
  result.plan_scale_search = scale;
  result.plan_scale_search_std = result.plan_scale_std;
  result.plan_scale_estimated = true;
  location.scale = scale;
  if (location.given)
    location.registration = registration_of(*location.given, scale);
  result.scale_search_seconds = seconds_since(clock);
}

}  // namespace floorgrid
