#include "floorgrid/pipeline/dual_localizer.hpp"

#include <chrono>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/pipeline/dual_pairs.hpp"
#include "floorgrid/pipeline/gridmap_localization.hpp"
#include "floorgrid/pipeline/plan_location.hpp"
#include "floorgrid/pipeline/plan_scale_search.hpp"

namespace floorgrid {

ParticleFilterOptions default_plan_filter_options() {
  ParticleFilterOptions options;
  options.recovery.max_augmented_fraction = 0.0;
  options.recovery.min_fast_slow_ratio = 0.0;
  options.recovery.min_beam_likelihood = 0.1;
  options.recovery.max_bad_scans = 10;
  options.convergence.min_beam_likelihood = 0.2;
  // No effective-sample-size test: on sparse logs (a scan every metre and 10-20 degrees) the
  // motion spreads the particles far wider than one sharp scan's posterior, so the weights
  // collapse onto a few particles in the right place (ESS < 1%) while the cloud is tight and
  // explains the scan; the spread and the beam likelihood already say whether it is sure.
  options.convergence.min_ess_ratio = 0.0;
  // No quick rejoining after a drop: a plan filter that lost its fit may come back a wall's
  // thickness or a door's width off, which only three good scans in a row tell apart (on the
  // simulated office with gaps in the scans, rejoining doubled the pairs' median error).
  options.convergence.rejoin_window = 0;
  return options;
}

ParticleFilterOptions default_grid_filter_options() {
  ParticleFilterOptions options;
  options.recovery.max_augmented_fraction = 0.0;
  options.recovery.min_fast_slow_ratio = 0.0;
  options.convergence.min_ess_ratio = 0.0;  // as the plan filter's
  // The gridmap holds what the laser sees: a filter in the right place explains most of a
  // scan (about 0.9 of the mean beam likelihood), one in a look-alike place far less.
  options.convergence.min_beam_likelihood = 0.5;
  options.recovery.min_beam_likelihood = 0.35;
  // Global localization scores a lattice of headings 2.5 degrees apart, not 5: with the
  // gridmap's sharp likelihood (sigma_hit 0.1 m) a heading 2.5 degrees off moves a wall 10 m
  // away by 0.44 m, and which of two look-alike places fits the first scan best became a matter
  // of how each fell on the lattice (ACES seed 3: the symmetric quadrant 37 m away, for 50 scans).
  options.seeding.headings = 144;
  return options;
}

MapFilterOptions default_plan_options() {
  return {.filter = default_plan_filter_options(),
          .model = ObservationModelKind::likelihood_field,
          .likelihood = {.sigma_hit = 0.15,
                         .z_hit = 0.8,
                         .z_rand = 0.2,
                         .max_distance = 2.0,
                         .beam_weight = 0.5,
                         .unknown_is_free = true},
          .observation = {.max_beams = 60},
          .runner = {}};
}

MapFilterOptions default_grid_options() {
  return {.filter = default_grid_filter_options(),
          .model = ObservationModelKind::likelihood_field,
          .likelihood = {.sigma_hit = 0.1,
                         .z_hit = 0.9,
                         .z_rand = 0.1,
                         .max_distance = 2.0,
                         .beam_weight = 0.5,
                         .unknown_is_free = true},
          .observation = {.max_beams = 60},
          .runner = {}};
}

std::uint64_t stream_seed(std::uint64_t seed, SeedStream stream, std::uint64_t index) {
  return seed + static_cast<std::uint64_t>(stream) + index;
}

namespace {

/// Bad input is refused before any work: too short a log, a scale that is not a positive
/// number, a log without a single laser return.
void validate_inputs(const DualLocalizerInputs& inputs, const DualLocalizerOptions& options) {
  if (inputs.log.scans.size() < 2)
    throw InputError("the log needs at least two laser scans", {}, 0, "log");
  if (inputs.plan_scale && !(*inputs.plan_scale > 0.0 && std::isfinite(*inputs.plan_scale)))
    throw InputError("must be a number > 0 or auto", {}, 0, "floorplan_scale");
  validate(options.scale_search.range);
  for (const LaserScan& scan : inputs.log.scans) {
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      if (scan.is_return(i))
        return;
    }
  }
  throw InputError(
      "no scan of the log holds a laser return (every reading is invalid, zero or at the max "
      "range): check the log's laser settings",
      {}, 0, "log");
}

/// A result with one empty record per scan.
DualLocalization empty_result(std::size_t scans) {
  DualLocalization result;
  result.scans.resize(scans);
  for (std::size_t i = 0; i < scans; ++i)
    result.scans[i].scan = i;
  return result;
}

/// The pairs of every usable scan, less the scans that disagree with the rest.
void make_dual_pairs(const DualMaps& maps, const RobotLog& log, const DualLocalizerOptions& options,
                     DualLocalization& result) {
  const auto clock = std::chrono::steady_clock::now();
  make_pairs(result, log, maps.plan_walls(), maps.grid_walls(), options.pairs, options.pose_pull,
             options.refine_poses);
  drop_outlier_scans(result, options.outlier_scans);
  result.pairs_seconds = seconds_since(clock);
  summarize_convergence(result);
}

}  // namespace

DualLocalization localize_dual(const DualLocalizerInputs& inputs,
                               const DualLocalizerOptions& options,
                               const DualProgressCallback& progress) {
  validate_inputs(inputs, options);
  DualLocalization result = empty_result(inputs.log.scans.size());
  const auto clock = std::chrono::steady_clock::now();
  const DualMaps maps(inputs, options, result.notes);

  // 1. Localize on the gridmap.
  const GridmapLocalization gridmap = localize_on_gridmap(maps, inputs, options, result, progress);
  result.grid_seconds = seconds_since(clock);
  if (!result.status.ok)
    return result;
  result.localize_seconds += result.grid_seconds - result.global_localization_seconds;

  // 2. Locate the run on the plan.
  PlanLocation location = locate_run_on_plan(maps, inputs, gridmap, options, result);

  // 3. Search the plan scale.
  if (!inputs.plan_scale && !location.from_maps)
    search_plan_scale(maps, inputs.log, options, location, result);

  // 4 and 5. Track the plan, checked against the gridmap filter; refit the scale.
  track_plan_and_refit_scale(maps, inputs.log, options, location, result, progress,
                             inputs.plan_geometry != nullptr);

  // The pairs.
  make_dual_pairs(maps, inputs.log, options, result);
  return result;
}

}  // namespace floorgrid
