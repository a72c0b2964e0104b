#include "floorgrid/pipeline/plan_location.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "floorgrid/pipeline/plan_scale_search.hpp"

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

namespace {

// The scales to search: around the direct registration of the gridmap on the plan when it is
// clear, else the options' range. The maps' registration is the one align_maps made when the
// maps were aligned first, else one made here.
ScaleRange scale_range(const DualMaps& maps, const DualLocalizerInputs& inputs,
                       const DualLocalizerOptions& options, DualLocalization& result,
                       std::optional<MapSimilarity>& clear) {
  const PlanLocationOptions& step = options.plan_location;
  if (inputs.plan_scale || !step.register_maps)
    return options.scale_search.range;
  const MapRegistration reg =
      inputs.maps ? inputs.maps->registration
                  : register_maps(maps.gridmap(), inputs.plan, plan_walls_of(inputs.plan_geometry),
                                  step.map_registration);
  if (!reg.found || reg.best.score < step.map_min_score) {
    result.notes.push_back(
        fmt::format("the gridmap could not be registered on the plan directly ({} candidates, best "
                    "score {:.2f}, needs "
                    "{:.2f}): the scale is searched over {:.2f}-{:.2f}",
                    reg.candidates, reg.best.score, step.map_min_score,
                    options.scale_search.range.min, options.scale_search.range.max));
    return options.scale_search.range;
  }
  const double scale = 1.0 / reg.best.transform.scale;  // world metres per plan metre
  result.notes.push_back(fmt::format(
      "gridmap registered on the plan: scale {:.4f}, turned {:.1f} deg, score {:.2f} ({:.0f}% "
      "of the gridmap's walls on the plan's, {:.0f}% of the plan's walls in free space; "
      "runner-up {:.2f} at scale {:.4f}) in {:.1f} s",
      scale, reg.best.transform.theta * 180.0 / std::numbers::pi, reg.best.score,
      100.0 * reg.best.on_walls, 100.0 * reg.best.in_free_space, reg.runner_up().score,
      1.0 / reg.runner_up().transform.scale, reg.seconds));
  const bool is_clear = reg.best.score - reg.runner_up().score >= step.map_clear_margin;
  const ScaleRange& usual = options.scale_search.range;
  // A clear registration's scale and pose are kept as they are: the plan filter's search and
  // refit are biased by how the walls are drawn (a raster's thick strokes: -0.2 to -1%; a DXF's
  // lines traced around them: -0.25 to -0.56% on the semi-real datasets), the registration is
  // not (within 0.15% on every raster and DXF plan of the semi-real matrix, drawn where the
  // laser saw the walls; on architects' drawings it is low by the outer walls' faces, which
  // ScaleRefitOptions::raise_registered_scale takes up).
  if (is_clear)
    clear = reg.best.transform;
  if (scale >= usual.min && scale <= usual.max)
    return usual;
  return {scale / (1.0 + step.map_scale_margin), scale * (1.0 + step.map_scale_margin)};
}

// The maps' accepted alignment, when the run may start from it.
const MapAlignment* maps_prior(const DualLocalizerInputs& inputs, const PlanLocationOptions& step) {
  if (!step.start_from_maps || !inputs.maps || !inputs.maps->accepted || !inputs.maps->warp)
    return nullptr;
  return inputs.maps;
}

// The plan scale as a clear registration gives it, kept through the run (not refitted).
void keep_registration_scale(const MapSimilarity& clear, PlanLocation& location,
                             DualLocalization& result) {
  location.keep_scale = true;
  location.scale = 1.0 / clear.scale;
  location.scale_sigma = 0.0;
  result.plan_scale_estimated = true;
  result.plan_scale_search = location.scale;
  // The registration gives no spread of its scale: none is claimed (0), and the note says so.
  result.plan_scale_search_std = 0.0;
  result.plan_scale_std = 0.0;
  result.notes.push_back("the plan scale's uncertainty is not estimated (taken from the maps)");
}

}  // namespace

PlanLocation locate_run_on_plan(const DualMaps& maps, const DualLocalizerInputs& inputs,
                                const GridmapLocalization& gridmap,
                                const DualLocalizerOptions& options, DualLocalization& result) {
  const auto clock = std::chrono::steady_clock::now();
  const PlanLocationOptions& step = options.plan_location;
  std::optional<MapSimilarity> clear;
  const ScaleRange range = scale_range(maps, inputs, options, result, clear);
  PlanLocation location;
  location.given = gridmap.start;
  location.scale = inputs.plan_scale.value_or(0.5 * (range.min + range.max));
  location.scale_sigma =
      inputs.plan_scale ? 0.0 : options.scale_search.initial_sigma_share * (range.max - range.min);
  const Pose2 grid_start =
      location.given ? location.given->grid : result.scans[*gridmap.first_converged].grid.pose;
  const MapAlignment* prior = maps_prior(inputs, step);
  if (!location.given && prior) {
    // The maps were aligned first: the plan filter starts where their bent map puts the
    // gridmap filter's pose, and the dual check judges the plan filter by that map.
    const auto warp = std::make_shared<const MapWarp>(*prior->warp);
    location.from_maps = true;
    if (clear) {
      keep_registration_scale(*clear, location, result);  // (see scale_range)
      location.scale_at_faces = prior->faces.fitted;
    } else if (!inputs.plan_scale) {
      // ... fitted on the run's scans placed on the plan by the bent map, from its scale within
      // its spread: a drawing wrong in places, or a bent gridmap, has no one scale.
      search_plan_scale_from_maps(maps, inputs.log, options, *warp, prior->scale.scale,
                                  std::max(prior->scale.relative_std, step.maps_min_scale_share),
                                  location, result);
    }
    location.registration = PlanRegistration(warp, location.scale);
    location.start_sigma = step.maps_start_sigma / location.scale;
    location.start_heading_sigma = step.maps_start_heading_sigma;
    result.plan_start_scan = result.grid_start_scan;
    result.notes.push_back(fmt::format(
        "the run starts from the maps' alignment: scale {:.4f} (+- {:.1f}% over the bent map; "
        "its least-squares similarity {:.4f}), the plan filter where it puts the gridmap "
        "filter's pose",
        prior->scale.scale, 100.0 * prior->scale.relative_std, prior->scale.similarity_scale));
  } else if (!location.given && clear) {
    // The maps agree on one similarity: the plan filter starts where it puts the gridmap
    // filter's pose, at its scale.
    location.from_maps = true;
    keep_registration_scale(*clear, location, result);
    location.registration = PlanRegistration(grid_start, clear->apply(grid_start), location.scale);
    location.start_sigma = step.given_start_sigma;
    location.start_heading_sigma = step.given_start_heading_sigma;
    result.plan_start_scan = result.grid_start_scan;
  } else if (location.given) {
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
