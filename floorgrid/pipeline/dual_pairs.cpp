#include "floorgrid/pipeline/dual_pairs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "floorgrid/pipeline/plan_tracking.hpp"
#include "floorgrid/pipeline/pose_pull.hpp"

namespace floorgrid {

namespace {

constexpr const char* kKeptRegisteredScale =
    "the plan scale is kept as the maps' registration gave it";

}  // namespace

bool usable_for_pairs(const ScanRecord& r, bool refine) {
  if (!(r.plan.converged && r.grid.converged) || !r.consistent)
    return false;
  return !refine || (r.plan.match.ok() && r.grid.match.ok());
}

ScaleRefit refit_plan_scale(DualLocalization& result, const RobotLog& log,
                            const WallField& plan_walls, const FilterRunnerOptions& plan_runner,
                            const ScaleRefitOptions& options, double scale, bool fit_shift,
                            double min_shift, bool registered, bool at_faces,
                            const GridRayCaster* plan_caster) {
  // Each scan reduced to its beams consistent with the plan at its pose as it is prepared: a
  // long run's full observations and their reduced copies are never held at once.
  std::vector<ScanObservation> points;
  std::vector<Pose2> poses;
  std::vector<std::size_t> which;
  for (const ScanRecord& r : result.scans) {
    if (!usable_for_pairs(r, true))
      continue;
    ScanObservation observation =
        make_observation(log.scans[r.scan], plan_runner.match_observation);
    if (plan_caster)
      observation = beam_consistent(observation, *plan_caster, r.plan.match.pose, scale,
                                    plan_runner.beam_tolerance);
    points.push_back(std::move(observation));
    poses.push_back(r.plan.match.pose);
    which.push_back(r.scan);
  }
  if (points.size() < options.min_scans) {
    result.notes.push_back("too few matched scans to refit the plan scale: kept the search's");
    return {scale};
  }
  std::vector<const ScanObservation*> views;
  views.reserve(points.size());
  for (const ScanObservation& p : points)
    views.push_back(&p);
  const auto fit_with = [&](bool shift) {
    return fit_scale(plan_walls, views, poses, scale, plan_runner.match, options.max_iterations,
                     options.jackknife_blocks, shift);
  };
  ScaleFit fit = fit_with(fit_shift);
  ScaleRefit refit;
  if (fit_shift) {
    result.plan_surface_shift = fit.surface_shift * fit.scale;
    result.plan_surface_shift_std = fit.surface_shift_std * fit.scale;
    const bool shift_used = std::abs(result.plan_surface_shift) >= min_shift;
    result.notes.push_back(fmt::format(
        "the plan's walls were met {:.3f} m (+-{:.3f} m) nearer the laser than drawn{}",
        result.plan_surface_shift, result.plan_surface_shift_std,
        shift_used ? ", fitted with the scale" : ": on their lines, so the scale is fitted alone"));
    // The walls' faces lie on the drawn lines: a registered scale is kept with the scans' poses,
    // unless the registration did not meet the outer walls' faces (then it lies low) and the
    // scale refitted alone comes out higher (lower still is the walls' thickness biasing the
    // refit too).
    const bool on_lines_registered = !shift_used && registered;
    const bool may_raise = !at_faces && options.raise_registered_scale;
    std::optional<ScaleFit> alone;
    if (!on_lines_registered || may_raise)
      alone = fit_with(false);
    if (on_lines_registered && !(may_raise && alone->scale > scale)) {
      result.notes.push_back(kKeptRegisteredScale);
      return {scale};
    }
    if (on_lines_registered) {
      result.notes.push_back(fmt::format(
          "the scale refitted alone, {:.4f}, lies above the maps' registration's {:.4f}, which "
          "did not meet the outer walls' faces (a drawn outline registered on the laser's comes "
          "out small): the refit is used",
          alone->scale, scale));
    }
    if (shift_used) {
      refit.scale_at_drawn_walls = alone->scale;
      result.notes.push_back(
          fmt::format("fitted on the drawn walls without it, as the maps' registration meets "
                      "them, the plan scale would be {:.4f}",
                      alone->scale));
    } else {
      fit = std::move(*alone);  // as the fit was without the shift
    }
  }
  result.plan_scale_std = fit.scale_std;
  for (std::size_t k = 0; k < which.size(); ++k)
    result.scans[which[k]].plan.match.pose = fit.poses[k];
  result.notes.push_back("plan scale refitted on " + std::to_string(fit.scans) +
                         " scans by joint scan matching");
  refit.scale = fit.scale;
  return refit;
}

void track_plan_and_refit_scale(const DualMaps& maps, const RobotLog& log,
                                const DualLocalizerOptions& options, PlanLocation& location,
                                DualLocalization& result, const DualProgressCallback& progress,
                                bool vector_plan) {
  const ScaleRefitOptions& refit_options = options.scale_refit;
  // Whether the refit fits the shift: decided by the first pass's (min_shift; none with
  // always), then kept, so that a pass tracked at a scale the shift moved is refitted the same
  // way.
  bool fit_shift = refit_options.surface_shift != SurfaceShift::never;
  double min_shift = 0.0;
  if (refit_options.surface_shift == SurfaceShift::automatic) {
    min_shift = refit_options.min_shift;
    if (!vector_plan)
      min_shift = std::max(
          min_shift, refit_options.min_shift_pixels * maps.plan().resolution() * location.scale);
  }
  const bool refit_scale =
      result.plan_scale_estimated && options.refine_poses && refit_options.enabled &&
      (!location.keep_scale || (refit_options.refit_registered_scale && fit_shift));
  if (location.keep_scale && !refit_scale)
    result.notes.push_back(kKeptRegisteredScale);
  // The last pass's result and location, refitted, kept while the plan is tracked again.
  std::optional<std::pair<DualLocalization, PlanLocation>> last;
  std::size_t last_matched = 0;
  for (int pass = 1;; ++pass) {
    auto clock = std::chrono::steady_clock::now();
    track_plan(maps, log, options, location, result, progress);
    result.localize_seconds += seconds_since(clock);
    if (!refit_scale)
      break;
    const auto matched = static_cast<std::size_t>(
        std::count_if(result.scans.begin(), result.scans.end(),
                      [](const ScanRecord& r) { return usable_for_pairs(r, true); }));
    if (last && static_cast<double>(matched) <
                    refit_options.retrack_min_share * static_cast<double>(last_matched)) {
      const double seconds = result.localize_seconds, search = result.scale_search_seconds;
      std::tie(result, location) = std::move(*last);
      result.localize_seconds = seconds;
      result.scale_search_seconds = search;
      result.notes.push_back(
          fmt::format("tracked again at the refitted scale, the plan matched {} scans where it had "
                      "matched {}: the last pass's poses and scale kept",
                      matched, last_matched));
      break;
    }
    clock = std::chrono::steady_clock::now();
    const ScaleRefit refitted = refit_plan_scale(
        result, log, maps.plan_walls(), options.plan.runner, refit_options, location.scale,
        fit_shift, pass == 1 ? min_shift : 0.0, location.keep_scale && pass == 1,
        location.scale_at_faces, maps.plan_rays());
    fit_shift = refitted.shift_used();
    const double refit = refitted.scale;
    result.scale_search_seconds += seconds_since(clock);
    const double change = std::abs(refit / location.scale - 1.0);
    if (change > refit_options.max_change) {
      result.plan_scale_std = result.plan_scale_search_std;
      result.notes.push_back("the scale refit went far from the search's: kept the search's");
      break;
    }
    location.scale = refit;
    result.plan_scale_at_drawn_walls = refitted.scale_at_drawn_walls;
    if (location.given)
      location.registration = registration_of(*location.given, refit);
    if (change <= refit_options.retrack_change || pass >= refit_options.max_plan_passes)
      break;
    result.notes.push_back("the plan tracked again with the refitted scale");
    last.emplace(result, location);
    last_matched = matched;
  }
  result.plan_scale = location.scale;
}

namespace {

/// The poses a usable scan's pairs are made from: the scan-matched ones when `refine`, else the
/// filters' means; nullopt (with the scan's beams counted in `rejections`) for a scan that
/// gives no pairs.
std::optional<std::pair<Pose2, Pose2>> pair_poses(const ScanRecord& record, const LaserScan& scan,
                                                  bool refine, PairRejections& rejections) {
  if (!(record.plan.converged && record.grid.converged)) {
    reject_scan(scan, rejections);
    return std::nullopt;
  }
  if (!record.consistent) {
    rejections.inconsistent += scan.ranges.size();
    return std::nullopt;
  }
  if (!refine)
    return std::pair{record.plan.pose, record.grid.pose};
  const ScanMatchFailure failure =
      record.plan.match.ok() ? record.grid.match.failure : record.plan.match.failure;
  if (failure == ScanMatchFailure::degenerate) {
    rejections.degenerate += scan.ranges.size();
    return std::nullopt;
  }
  if (failure != ScanMatchFailure::none) {
    rejections.unmatched += scan.ranges.size();
    return std::nullopt;
  }
  return std::pair{record.plan.match.pose, record.grid.match.pose};
}

/// The plan poses' pull along the robot's heading over `samples` (measure_pose_pull), with a
/// note saying what was done with it.
std::optional<PosePull> pull_of_pair_poses(DualLocalization& result,
                                           const std::vector<PullSample>& samples,
                                           const PosePullOptions& options) {
  if (!options.enabled)
    return std::nullopt;
  std::optional<PosePull> pull = measure_pose_pull(samples, result.plan_scale, options);
  if (!pull)
    return pull;
  result.notes.push_back(fmt::format(
      "the plan's poses stood {:.3f} m ahead of the gridmap's along the robot's heading (+-{:.3f} "
      "m, from {} scans revisited facing another way): {}",
      pull->along_m, pull->std_m, pull->scans,
      pull->applied ? "taken out of the pairs" : "not taken out (too uncertain or too large)"));
  return pull;
}

}  // namespace

void make_pairs(DualLocalization& result, const RobotLog& log, const WallField& plan_walls,
                const WallField& grid_walls, const PairExtractionOptions& options,
                const PosePullOptions& pull_options, bool refine) {
  std::vector<std::optional<std::pair<Pose2, Pose2>>> poses(result.scans.size());
  std::vector<PullSample> samples;
  for (std::size_t k = 0; k < result.scans.size(); ++k) {
    const LaserScan& scan = log.scans[result.scans[k].scan];
    poses[k] = pair_poses(result.scans[k], scan, refine, result.rejections);
    if (poses[k])
      samples.push_back({scan.timestamp, poses[k]->first, poses[k]->second});
  }
  result.pose_pull = pull_of_pair_poses(result, samples, pull_options);
  const double pull_m =
      result.pose_pull && result.pose_pull->applied ? result.pose_pull->along_m : 0.0;
  PairCollector pairs;
  for (std::size_t k = 0; k < result.scans.size(); ++k) {
    if (!poses[k])
      continue;
    ScanRecord& record = result.scans[k];
    const Pose2 plan_pose = without_pull(poses[k]->first, pull_m, result.plan_scale);
    const std::size_t before = pairs.size();
    extract_scan_pairs(log.scans[record.scan], plan_pose, result.plan_scale, poses[k]->second,
                       plan_walls, grid_walls, options, pairs, result.rejections);
    record.pairs = pairs.size() - before;
  }
  result.pairs = pairs.pairs();
}

void drop_outlier_scans(DualLocalization& result, const OutlierScanOptions& options) {
  std::vector<std::size_t> counts;
  counts.reserve(result.scans.size());
  for (const ScanRecord& r : result.scans)
    counts.push_back(r.pairs);
  const std::size_t before = static_cast<std::size_t>(result.pairs.size());
  reject_outlier_scans(result.pairs, counts, options);
  for (std::size_t k = 0; k < counts.size(); ++k)
    result.scans[k].pairs = counts[k];
  result.rejections.outlier_scan += before - static_cast<std::size_t>(result.pairs.size());
}

void summarize_convergence(DualLocalization& result) {
  std::optional<std::size_t> first;
  std::size_t both = 0;
  result.converged_periods.clear();
  for (const ScanRecord& r : result.scans) {
    const bool ok = r.plan.converged && r.grid.converged;
    if (ok && !first)
      first = r.scan;
    if (!ok)
      continue;
    ++both;
    if (!result.converged_periods.empty() && result.converged_periods.back().second + 1 == r.scan) {
      result.converged_periods.back().second = r.scan;
    } else {
      result.converged_periods.emplace_back(r.scan, r.scan);
    }
  }
  result.longest_gap = 0;
  for (std::size_t k = 1; k < result.converged_periods.size(); ++k) {
    result.longest_gap =
        std::max(result.longest_gap,
                 result.converged_periods[k].first - result.converged_periods[k - 1].second - 1);
  }
  if (first) {
    result.converged_fraction =
        static_cast<double>(both) / static_cast<double>(result.scans.size() - *first);
  } else {
    result.notes.push_back("the two filters were never converged at the same time: no pairs");
  }
}

}  // namespace floorgrid
