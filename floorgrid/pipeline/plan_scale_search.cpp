#include "floorgrid/pipeline/plan_scale_search.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
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
                                 const ObservationModel& model, const DualLocalizerOptions& options,
                                 const PlanLocation& location, const Pose2& start) {
  ParticleFilterOptions filter_options = options.plan.filter;
  filter_options.scale_walk = options.scale_search.walk;
  ParticleFilter filter(filter_options, stream_seed(options.seed, SeedStream::scale_search));
  filter.initialize_tracking(plan_start(start, location.start_sigma, location.start_heading_sigma,
                                        location.scale, location.scale_sigma),
                             maps.plan());
  FilterRunnerOptions runner = options.plan.runner;
  runner.improved_proposal = false;  // the proposal would match at the mean scale
  runner.refine = false;
  return FilterRunner(std::move(filter), model, maps.plan_walls(), log,
                      options.scale_search.observation, runner);
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
  FilterRunner runner =
      scale_search_runner(maps, log, model.model(), options, location, result.start.plan);
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

namespace {

/// The sure scans the dead reckoning follows: of every k-th scan of the log (k from the log's
/// length, so the same scans whatever the seed), those where the gridmap filter was sure,
/// with their gridmap poses.
struct ReckonedScans {
  std::size_t every = 1;  ///< log scans between two reckoned ones
  std::vector<std::size_t> scans;
  std::vector<Pose2> grid_poses;
  std::vector<ScanObservation> observations;
};

ReckonedScans reckoned_scans(const RobotLog& log, const DualLocalization& result,
                             const DualLocalizerOptions& options, std::size_t at_most) {
  ReckonedScans out;
  out.every = std::max<std::size_t>(
      1, (log.scans.size() + at_most - 1) / std::max<std::size_t>(1, at_most));
  for (const ScanRecord& r : result.scans) {
    if (r.scan % out.every != 0 || !r.grid.converged || (r.grid.matched && !r.grid.match.ok()))
      continue;
    out.scans.push_back(r.scan);
    out.grid_poses.push_back(r.grid.matched ? r.grid.match.pose : r.grid.pose);
    out.observations.push_back(
        make_observation(log.scans[r.scan], options.plan.runner.match_observation));
  }
  return out;
}

/// Dead reckoning on the plan at one scale, in segments of `segment` scans: each segment starts
/// where the maps put its first scan, and each scan after it is predicted by the gridmap
/// filter's motion since the last (world metres over `scale`) and matched onto the plan's
/// walls; the endpoints that land on them are counted. Along a corridor a scan cannot place
/// the robot, so a wrong scale carries it past the door frames and corners the next scans
/// should meet: the right scale meets the most. Short segments keep one lost match from
/// losing the rest of the run (one reckoning through the whole run made the count jump by 3x
/// between neighbouring scales, and the best scale a matter of the seed: fr079's ranged over
/// 1.115-1.174 on seeds 1-10; in segments of 12 scans seeds 1, 4 and 7 give 1.147-1.151).
std::size_t reckoned_inliers(const DualMaps& maps, const ReckonedScans& run, const MapWarp& warp,
                             double scale, std::size_t segment,
                             const DualLocalizerOptions& options) {
  const ScanMatchOptions& match = options.plan.runner.match;
  std::size_t inliers = 0;
  Pose2 plan;
  const std::size_t block = segment * run.every;  // log scans per segment
  for (std::size_t k = 0; k < run.scans.size(); ++k) {
    if (k == 0 || run.scans[k] / block != run.scans[k - 1] / block) {
      plan = warp.apply(run.grid_poses[k]);
    } else {
      const Pose2 step = run.grid_poses[k - 1].between(run.grid_poses[k]);
      plan = plan.compose({step.x / scale, step.y / scale, step.theta});
    }
    const ScanMatch m = match_with(maps.plan_walls(), run.observations[k], plan, scale, match,
                                   maps.plan_rays(), options.plan.runner.beam_tolerance);
    if (m.ok()) {
      plan = m.pose;
      inliers += m.inliers;
    }
  }
  return inliers;
}

}  // namespace

// The dead reckoning's counts are noisy (a match found or lost moves hundreds of endpoints),
// their hump is not: the fit follows the hump where the largest count follows the noise.
double hump_top(const std::vector<double>& scales, const std::vector<std::size_t>& inliers,
                double share) {
  if (scales.empty() || scales.size() != inliers.size())
    throw std::invalid_argument("hump_top: needs one count per scale, and at least one scale");
  const auto [low, high] = std::minmax_element(inliers.begin(), inliers.end());
  const std::size_t best = static_cast<std::size_t>(high - inliers.begin());
  const double floor = static_cast<double>(*low) + share * static_cast<double>(*high - *low);
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  const double centre = scales[best];
  double first = centre, last = centre;  // the fitted scales' extent
  for (std::size_t k = 0; k < scales.size(); ++k) {
    if (static_cast<double>(inliers[k]) < floor)
      continue;
    const double x = scales[k] / centre - 1.0;
    const Eigen::Vector3d row(1.0, x, x * x);
    normal += row * row.transpose();
    right += row * static_cast<double>(inliers[k]);
    first = std::min(first, scales[k]);
    last = std::max(last, scales[k]);
  }
  const Eigen::Vector3d c = normal.ldlt().solve(right);
  if (!(c[2] < 0.0) || !c.allFinite())
    return centre;
  const double vertex = centre * (1.0 - 0.5 * c[1] / c[2]);
  return vertex >= first && vertex <= last ? vertex : centre;
}

void search_plan_scale_from_maps(const DualMaps& maps, const RobotLog& log,
                                 const DualLocalizerOptions& options, const MapWarp& warp,
                                 double prior, double prior_relative_std, PlanLocation& location,
                                 DualLocalization& result) {
  const auto clock = std::chrono::steady_clock::now();
  const ScaleSearchOptions& search = options.scale_search;
  const ReckonedScans run = reckoned_scans(log, result, options, search.maps_scans);
  if (run.scans.size() < options.scale_refit.min_scans) {
    result.notes.push_back(fmt::format(
        "too few of the gridmap filter's scans ({}) to search the plan scale on: the maps' "
        "scale is used",
        run.scans.size()));
    location.scale = prior;
    return;
  }
  // The maps' scale +- its spread, the top of the counts' hump.
  const double range = std::clamp(search.maps_sigmas * prior_relative_std, search.maps_min_range,
                                  search.maps_max_range);
  const int steps = std::max(1, search.profile_steps);
  const std::size_t segment = std::max<std::size_t>(2, search.maps_segment_scans);
  std::vector<double> scales;
  for (int k = -steps; k <= steps; ++k)
    scales.push_back(prior * (1.0 + range * k / steps));
  std::vector<std::size_t> inliers(scales.size(), 0);
  parallel_tasks(scales.size(), options.threads, [&](std::size_t k) {
    inliers[k] = reckoned_inliers(maps, run, warp, scales[k], segment, options);
  });
  const double scale = hump_top(scales, inliers, search.maps_fit_share);
  result.notes.push_back(fmt::format(
      "plan scale {:.4f} by dead reckoning {} of the gridmap filter's scans on the plan from "
      "where the maps put them, over the maps' {:.4f} +- {:.1f}%",
      scale, run.scans.size(), prior, 100.0 * range));
  location.scale = scale;
  location.scale_sigma = 0.0;
  location.keep_scale = true;
  result.plan_scale_estimated = true;
  result.plan_scale_search = scale;
  // The lattice's resolution: the scale is known to about a step of it.
  result.plan_scale_search_std = scale * range / steps;
  result.plan_scale_std = result.plan_scale_search_std;
  result.scale_search_seconds += seconds_since(clock);
}

}  // namespace floorgrid
