#include "floorgrid/pipeline/plan_location.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

namespace floorgrid {

namespace {

/// The endpoints of every scan the gridmap filter was sure of (converged, and matched when it
/// was matched), seen from its poses, as one submap in the frame of `origin`.
ScanObservation sure_submap(const RobotLog& log, const DualLocalization& result,
                            const Pose2& origin, const SubmapOptions& options) {
  std::vector<std::size_t> scans;
  std::vector<Pose2> poses;
  for (const ScanRecord& r : result.scans) {
    if (r.grid.converged && (!r.grid.matched || r.grid.match.ok())) {
      scans.push_back(r.scan);
      poses.push_back(r.grid.matched ? r.grid.match.pose : r.grid.pose);
    }
  }
  return build_submap(log, scans, poses, origin, options);
}

}  // namespace

PlanRegistration registration_of(const StartPoses& start, double scale) {
  return PlanRegistration(start.grid, start.plan, scale);
}

TrackingStart plan_start(const Pose2& pose, double position_sigma, double heading_sigma,
                         double scale, double scale_sigma) {
  return TrackingStart{.pose = pose,
                       .position_sigma = position_sigma,
                       .heading_sigma = heading_sigma,
                       .scale = scale,
                       .scale_sigma = scale_sigma};
}

PlanLocation locate_run_on_plan(const DualMaps& maps, const DualLocalizerInputs& inputs,
                                const GridmapLocalization& gridmap,
                                const DualLocalizerOptions& options, DualLocalization& result) {
  const auto clock = std::chrono::steady_clock::now();
  const ScaleRange& range = options.scale_search.range;
  const PlanLocationOptions& step = options.plan_location;
  PlanLocation location;
  location.given = gridmap.start;
  location.scale = inputs.plan_scale.value_or(0.5 * (range.min + range.max));
  location.scale_sigma =
      inputs.plan_scale ? 0.0 : options.scale_search.initial_sigma_share * (range.max - range.min);
  const Pose2 grid_start =
      location.given ? location.given->grid : result.scans[*gridmap.first_converged].grid.pose;
  if (location.given) {
    location.registration = registration_of(*location.given, location.scale);
    location.start_sigma = step.given_start_sigma;
    location.start_heading_sigma = step.given_start_heading_sigma;
  } else {
    const ScanObservation submap = sure_submap(inputs.log, result, grid_start, step.submap);
    const LikelihoodFieldModel wide(maps.plan(), step.registration_likelihood);
    const std::optional<ScaleRange> scales =
        inputs.plan_scale ? std::nullopt : std::optional<ScaleRange>(range);
    result.registration = register_on_plan(maps.plan(), wide, submap, grid_start, scales,
                                           location.scale, step.registration, options.threads);
    location.registration = result.registration->registration;
    if (!inputs.plan_scale) {
      // The registration's lattice step of scales is how far off its scale may be.
      location.scale = location.registration.scale();
      location.scale_sigma =
          (range.max - range.min) / std::max(1, step.registration.seeding.scales);
    }
    location.start_sigma = step.registered_start_sigma;
    location.start_heading_sigma = step.registered_start_heading_sigma;
    result.plan_start_scan = result.grid_start_scan;
  }
  result.global_localization_seconds += seconds_since(clock);
  result.start.grid = grid_start;
  result.start.plan =
      location.given ? location.given->plan : location.registration.plan_pose(grid_start);
  return location;
}

}  // namespace floorgrid
