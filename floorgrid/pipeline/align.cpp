#include "floorgrid/pipeline/align.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/memory_usage.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/mapping/model_selection.hpp"
#include "floorgrid/mapping/piecewise_affine.hpp"
#include "floorgrid/maps/distance_field.hpp"

namespace floorgrid {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The bias the pairs share (PairSourceOptions::shared_bias), world metres.
SharedBias measure_shared_bias(const AlignmentOptions& options, const Alignment& a) {
  SharedBias b;
  const ReferencePairs& pairs = a.localization.pairs;
  if (options.sources.shared_bias) {
    if (a.pairs_from != PairSource::maps && a.sources && a.sources->compared && a.sources->agree) {
      b.sources_m = a.sources->disagreement_local_median_m;
      b.from = "agreement";
    } else if (a.pairs_from == PairSource::maps && a.maps && pairs.size() > 0) {
      b.sources_m = a.maps->scale.relative_std * radius_of_gyration(pairs.points_in_grid);
      b.from = "maps";
    }
    // The faces neither source took out: the maps' accepted fit did not use them, and the run's
    // pairs (when used) were not refitted with the walls' surface shift.
    const bool run_took_them_out =
        a.pairs_from != PairSource::maps && a.localization.plan_scale_at_drawn_walls > 0.0;
    if (a.maps && a.maps->accepted && !a.maps->faces.fitted && !run_took_them_out) {
      const double scale = a.maps->registration.best.transform.scale;
      const double outer = scale > 0.0 ? a.maps->faces.exterior_offset / scale : 0.0;
      if (std::isfinite(outer) && outer > 0.0 && outer <= a.maps->options.faces.max_offset)
        b.faces_m = outer;
    }
  }
  b.std_m = std::hypot(b.sources_m, b.faces_m);
  const double floor = options.models.mapping.uncertainty.shared_std;
  if (floor > b.std_m) {
    b = {};
    b.std_m = floor;
    b.from = "option";
  }
  return b;
}

/// Every model fitted to the pairs and judged against the truth and against the gridmap's
/// walls; the model `auto` chose.
void fit_and_judge_models(const AlignmentInputs& in, const AlignmentOptions& options, Alignment& a,
                          const AlignmentProgressCallback& progress) {
  const ReferencePairs& pairs = a.localization.pairs;
  a.shared_bias = measure_shared_bias(options, a);
  ModelComparisonOptions models = options.models;
  models.mapping.uncertainty.shared_std = a.shared_bias.std_m;
  const auto fit_start = Clock::now();
  std::vector<ModelReport> reports = compare_models(
      pairs, a.domain, a.truth, a.pair_noise, models,
      [&](const std::string& model, std::size_t done, std::size_t total) {
        if (progress)
          progress({"fit", model, done, total});
      },
      a.localized_pairs.size() > 0 ? &a.localized_pairs : nullptr);
  const double total_seconds = seconds_since(fit_start);
  double wall_seconds = 0.0;
  for (ModelReport& r : reports) {
    a.evaluate_seconds += r.evaluate_seconds;
    ModelAlignment m;
    if (r.model) {
      const auto wall_start = Clock::now();
      const Eigen::Matrix2Xd mapped = r.model->forward_batch(in.plan_wall_samples);
      m.wall_distance =
          wall_distance(in.plan_wall_samples, mapped, in.gridmap, pairs.points_in_plan,
                        options.near_pairs, options.wall_distance_cap);
      if (const auto* chooser = dynamic_cast<const AutoMapping*>(r.model.get()))
        a.chosen = chooser->chosen().name();
      wall_seconds += seconds_since(wall_start);
    }
    m.report = std::move(r);
    a.models.push_back(std::move(m));
  }
  a.fit_seconds = total_seconds - a.evaluate_seconds;
  a.evaluate_seconds += wall_seconds;
}

}  // namespace

ErrorStatistics pair_errors(const ReferencePairs& pairs, const GroundTruth& truth) {
  std::vector<double> errors(static_cast<std::size_t>(pairs.size()));
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    errors[static_cast<std::size_t>(i)] =
        (truth(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
  return error_statistics(std::move(errors));
}

DatasetTruth dataset_truth(const AlignmentInputs& in) {
  if (in.truth_warp)
    return {in.truth_warp, "warp"};
  if (in.manual_pairs && in.manual_pairs->size() >= 3) {
    // Through every hand pair, folds and all (the thesis's truth; dt's untangling would drop
    // the pairs that disagree). Shared by the function: the truth outlives this call.
    std::shared_ptr<PointMapping> model =
        std::make_shared<PiecewiseAffineMapping>(MappingCommonOptions{}, false);
    model->fit(*in.manual_pairs);
    return {[model](const Eigen::Vector2d& p) { return model->forward(p); }, "manual_pairs_hull"};
  }
  return {};
}

EvaluationDomain truth_domain(const AlignmentInputs& in, const DatasetTruth& truth,
                              double spacing) {
  EvaluationDomain d{"none", Eigen::Matrix2Xd(2, 0), spacing, std::nullopt};
  if (truth.kind == "warp") {
    d = in.plan ? warp_domain(*in.plan, in.gridmap, *truth.plan_to_grid, spacing)
                : warp_domain(in.plan_wall_samples, in.gridmap, *truth.plan_to_grid, spacing);
  } else if (truth.kind == "manual_pairs_hull") {
    d = in.plan ? hull_domain(*in.plan, in.manual_pairs->points_in_plan, spacing)
                : hull_domain(in.plan_wall_samples, in.manual_pairs->points_in_plan, spacing);
  }
  if (truth.plan_to_grid)
    d.truth_plan_scale = truth_plan_scale(d, *truth.plan_to_grid);
  return d;
}

WallDistance wall_distance(const Eigen::Matrix2Xd& samples, const Eigen::Matrix2Xd& mapped,
                           const OccupancyGrid& gridmap, const Eigen::Matrix2Xd& pair_points,
                           double near, double cap) {
  WallDistance w;
  const DistanceField walls = occupied_distance_field(gridmap, cap);
  const PointIndex2D pairs(pair_points);
  std::vector<double> near_distances;
  w.distances.reserve(static_cast<std::size_t>(samples.cols()));
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    const double d = walls.at(mapped.col(i));
    w.distances.push_back(d);
    if (pairs.size() > 0 && pairs.nearest(samples.col(i)).distance <= near)
      near_distances.push_back(d);
  }
  w.points = w.distances.size();
  w.median_m = w.distances.empty() ? 0.0 : upper_median(w.distances);
  w.near_points = near_distances.size();
  w.near_median_m = near_distances.empty() ? 0.0 : upper_median(near_distances);
  return w;
}

const char* to_string(PairSource source) {
  switch (source) {
    case PairSource::run:
      return "run";
    case PairSource::maps:
      return "maps";
    case PairSource::both:
      return "both";
  }
  return "run";
}

PairSource parse_pair_source(const std::string& name, const std::string& field) {
  for (const PairSource s : {PairSource::run, PairSource::maps, PairSource::both}) {
    if (name == to_string(s))
      return s;
  }
  throw InputError(field + " must be run, maps or both (got \"" + name + "\")");
}

namespace {

// Why the maps' alignment was not accepted, with its figures (the fitness first).
std::string no_alignment_message(const MapAlignment& m) {
  return fmt::format(
      "no alignment found from the maps alone (fitness {:.2f}: {:.0f}% of the gridmap's walls on "
      "the plan's, {:.0f}% of the plan's walls in space the gridmap saw free; ambiguity {:.2f}): "
      "{}",
      m.fit.score, 100.0 * m.fit.on_walls, 100.0 * m.fit.in_free_space, m.ambiguity, m.diagnosis);
}

// The maps aligned (align_maps), with a note of what it found for the localization's story.
MapAlignment align_on_maps(const AlignmentInputs& in, const AlignmentOptions& options,
                           std::vector<std::string>& notes) {
  MapAlignment m =
      align_maps(in.gridmap, in.plan_grid, plan_walls_of(in.plan),
                 options.localization.plan_location.map_registration, options.maps_only);
  const MapSimilarity& s = m.registration.best.transform;
  if (m.registration.found) {
    notes.push_back(fmt::format(
        "maps: the gridmap registered on the plan at scale {:.4f}, turned {:.1f} deg, score "
        "{:.2f} (runner-up {:.2f}), then bent onto it in {} stages: {} of {} gridmap wall points "
        "(on a straight wall) within {:.2f} m of a plan wall became pairs; fitness {:.2f} ({:.0f}% "
        "of the gridmap's "
        "walls on the plan's, {:.0f}% of the plan's walls in free space) in {:.1f} s",
        s.scale, s.theta * 180.0 / std::numbers::pi, m.registration.best.score,
        m.registration.runner_up().score, m.stages, m.pairs.size(), m.points,
        options.maps_only.pair_radius, m.fit.score, 100.0 * m.fit.on_walls,
        100.0 * m.fit.in_free_space, m.seconds));
    if (!m.faces.note.empty() && m.faces.note != "off")
      notes.push_back(
          fmt::format("maps: the registration refined on the walls' faces: {}", m.faces.note));
    if (m.runner_up) {
      notes.push_back(
          fmt::format("maps: the best other place, bent as well, has fitness {:.2f} (scale {:.4f}, "
                      "turned {:.1f} deg)",
                      m.runner_up->fit.score, m.runner_up->start.scale,
                      m.runner_up->start.theta * 180.0 / std::numbers::pi));
    }
  }
  if (!m.accepted)
    notes.push_back(no_alignment_message(m));
  return m;
}

// The plan scale the maps give: their registration's, with the bent map's spread of it.
void set_maps_scale(const MapAlignment& m, DualLocalization& l) {
  l.plan_scale = 1.0 / m.registration.best.transform.scale;
  l.plan_scale_std = l.plan_scale * m.scale.relative_std;
  l.plan_scale_estimated = true;
}

// The localization from the maps alone: their alignment's pairs and scale, or why none.
void localize_on_maps(const AlignmentInputs& in, const AlignmentOptions& options, Alignment& a) {
  DualLocalization& l = a.localization;
  a.maps = align_on_maps(in, options, l.notes);
  if (a.maps->registration.found)
    set_maps_scale(*a.maps, l);
  if (a.maps->accepted) {
    l.pairs = a.maps->pairs;
    return;
  }
  l.status = {false,
              no_alignment_message(*a.maps) +
                  ". Check that the plan and the gridmap show the same floor, or give a robot "
                  "run (log:)",
              "floorplan"};
}

// The maps' pairs after the run's.
void append_pairs(ReferencePairs& to, const ReferencePairs& from) {
  const Eigen::Index n = to.size(), k = from.size();
  to.points_in_plan.conservativeResize(2, n + k);
  to.points_in_grid.conservativeResize(2, n + k);
  to.points_in_plan.rightCols(k) = from.points_in_plan;
  to.points_in_grid.rightCols(k) = from.points_in_grid;
  if (to.has_weights() || from.has_weights()) {
    Eigen::VectorXd w(n + k);
    for (Eigen::Index i = 0; i < n; ++i)
      w[i] = to.weight(i);
    for (Eigen::Index i = 0; i < k; ++i)
      w[n + i] = from.weight(i);
    to.weights = w;
  }
}

// The pairs judged: the truth, the plan match, every model fitted and judged.
void judge_alignment(const AlignmentInputs& in, const AlignmentOptions& options, Alignment& a,
                     const AlignmentProgressCallback& progress);

// The plan match under `pairs` (plan_match.hpp), as align judges every source.
PlanMatch plan_match_of(const AlignmentInputs& in, const AlignmentOptions& options,
                        const ReferencePairs& pairs) {
  return judge_plan_match(in.gridmap, in.plan_grid, plan_walls_of(in.plan), pairs,
                          options.localization.plan_location.map_registration);
}

// Whether `match` passes the plan-match check the options set (both sources are held to it).
bool match_passes(const AlignmentOptions& options, const PlanMatch& match) {
  const PlanLocationOptions& location = options.localization.plan_location;
  return plan_match_accepted(match, location.min_plan_match, location.max_plan_walls_in_free_space);
}

// The maps' pairs instead of the run's: no wall slide or pair noise (no visits to compare),
// the maps' scale, and why.
void use_maps_pairs(Alignment& a, const std::string& why) {
  DualLocalization& l = a.localization;
  l.pairs = a.maps->pairs;
  l.status = {};
  set_maps_scale(*a.maps, l);
  a.localized_pairs = {};
  a.wall_slide.reset();
  a.pair_noise.reset();
  a.localized_pair_errors.reset();
  a.pairs_from = PairSource::maps;
  l.notes.push_back("the maps' pairs are used instead of the run's: " + why);
}

// Which pairs the job goes on with: the run's judged on their own (the plan match, how much of
// the building they cover) and against the maps' alignment; the maps' when only they pass or
// the plan match prefers them; none (the job fails) when neither passes.
void choose_pair_source(const AlignmentInputs& in, const AlignmentOptions& options, Alignment& a) {
  DualLocalization& l = a.localization;
  RunPairsSummary run{.localized = l.status.ok,
                      .failure = l.status.message,
                      .pairs = &l.pairs,
                      .plan_scale = l.plan_scale,
                      .noise_m = a.pair_noise ? std::sqrt(a.pair_noise->mean_square_m2) : 0.0,
                      .pair_scans = 0,
                      .scans = l.scans.size(),
                      .converged_fraction = l.converged_fraction,
                      .scale_at_drawn_walls = l.plan_scale_at_drawn_walls,
                      .match = {},
                      .match_accepted = false};
  for (const ScanRecord& r : l.scans)
    run.pair_scans += r.pairs > 0;
  if (run.localized && l.pairs.size() >= 3) {
    run.match = plan_match_of(in, options, l.pairs);
    run.match_accepted = match_passes(options, run.match);
  }
  a.sources = check_pair_sources(
      run, &*a.maps, in.gridmap, options.sources,
      [&](const ReferencePairs& pairs) { return plan_match_of(in, options, pairs); },
      [&](const PlanMatch& m) { return match_passes(options, m); });
  const PairSourceCheck& c = *a.sources;
  if (c.chosen == "maps") {
    use_maps_pairs(a, c.fallback);
    return;
  }
  if (c.chosen == "run") {
    a.plan_match = run.match;
    // Every maps' pair with --pairs-from both; else those where the run's do not reach.
    const ReferencePairs& added =
        a.pairs_from == PairSource::both && a.maps->accepted ? a.maps->pairs : c.fill;
    if (added.size() > 0) {
      append_pairs(l.pairs, added);
      if (a.localized_pairs.size() > 0)
        append_pairs(a.localized_pairs, added);
      a.pairs_from = PairSource::both;
      a.plan_match = plan_match_of(in, options, l.pairs);
      if (&added == &c.fill) {
        l.notes.push_back(fmt::format(
            "{} of the maps' pairs added where no run pair lies within {:.1f} m (the run agrees "
            "with the maps: {:.2f} m apart at the median)",
            added.size(), options.sources.fill_radius, c.disagreement_median_m));
      }
    }
    return;
  }
  // Neither passed. A run that made pairs keeps its plan match for the report; one whose pairs
  // pass that check but cannot vouch for the building fails here, with both reasons.
  a.plan_match = run.match;
  const std::string maps_failure =
      c.maps_failure.empty() ? no_alignment_message(*a.maps) : c.maps_failure;
  if (!c.maps_failure.empty())
    l.notes.push_back("the maps' pairs are not used: " + c.maps_failure);
  if (l.status.ok && run.match_accepted) {
    l.status = {false,
                c.run_failure + "; and " + maps_failure +
                    ". Check that the plan and the gridmap show the same floor and that the "
                    "gridmap's resolution is right",
                "log"};
  } else if (!l.status.ok) {
    l.status.message += ". The maps alone did not align either: " + maps_failure;
  }
}

}  // namespace

Alignment align(const AlignmentInputs& in, const AlignmentOptions& options,
                const AlignmentProgressCallback& progress) {
  validate(options.wall_slide);
  validate(options.maps_only);
  validate(options.sources);
  Alignment a;
  a.pairs_from = in.log.scans.empty() ? PairSource::maps : options.pairs_from;
  if (a.pairs_from == PairSource::maps) {
    if (progress)
      progress({"localize", "maps", 0, 1});
    localize_on_maps(in, options, a);
    a.peak_memory_mib["maps_alignment"] = peak_resident_mib();
    if (a.localization.status.ok) {
      judge_alignment(in, options, a, progress);
      a.peak_memory_mib["fit"] = peak_resident_mib();
    }
    return a;
  }
  // The maps first: their alignment seeds the run, checks its pairs and stands in for them.
  if (progress)
    progress({"localize", "maps", 0, 1});
  std::vector<std::string> maps_notes;
  a.maps = align_on_maps(in, options, maps_notes);
  a.peak_memory_mib["maps_alignment"] = peak_resident_mib();
  // The reference pairs, by dual Monte Carlo localization.
  // Where the faces were found, the run localizes on the plan grown to them.
  const OccupancyGrid& run_plan = a.maps->plan_at_faces ? *a.maps->plan_at_faces : in.plan_grid;
  a.localization = localize_dual({.plan = run_plan,
                                  .gridmap = in.gridmap,
                                  .log = in.log,
                                  .start = in.start,
                                  .plan_scale = in.plan_scale,
                                  .plan_geometry = in.plan,
                                  .maps = &*a.maps},
                                 options.localization, [&](const DualProgress& p) {
                                   if (progress)
                                     progress({"localize", p.phase, p.scan, p.scans});
                                 });
  a.peak_memory_mib["localize"] = peak_resident_mib();
  a.localization.notes.insert(a.localization.notes.begin(), maps_notes.begin(), maps_notes.end());
  if (a.localization.status.ok && options.wall_slide.iterations > 0 &&
      a.localization.pairs.size() > 0) {
    if (progress)
      progress({"fit", "wall slide", 0, 1});
    const auto slide_start = Clock::now();
    WallSlide slide = slide_pairs_along_walls(a.localization.pairs, in.gridmap, options.wall_slide,
                                              options.models.mapping);
    if (slide.applied()) {
      a.localized_pairs = std::move(a.localization.pairs);
      a.localization.pairs = std::move(slide.pairs);
    }
    slide.pairs = {};
    a.wall_slide = std::move(slide);
    a.wall_slide_seconds = seconds_since(slide_start);
    a.peak_memory_mib["wall_slide"] = peak_resident_mib();
  }
  // The pairs' noise is the run's: the maps' pairs have no visits to compare.
  if (a.localization.status.ok)
    a.pair_noise =
        pair_noise(a.localized_pairs.size() > 0 ? a.localized_pairs : a.localization.pairs);
  choose_pair_source(in, options, a);
  if (a.localization.status.ok) {
    judge_alignment(in, options, a, progress);
    a.peak_memory_mib["fit"] = peak_resident_mib();
  }
  return a;
}

namespace {

void judge_alignment(const AlignmentInputs& in, const AlignmentOptions& options, Alignment& a,
                     const AlignmentProgressCallback& progress) {
  // The truth, where it holds, and the pairs against it.
  const DatasetTruth truth = dataset_truth(in);
  a.truth = truth.plan_to_grid;
  a.domain = truth_domain(in, truth, options.domain_spacing);
  if (in.truth_warp && a.localization.pairs.size() > 0)
    a.pair_errors = pair_errors(a.localization.pairs, in.truth_warp);
  if (in.truth_warp && a.localized_pairs.size() > 0)
    a.localized_pair_errors = pair_errors(a.localized_pairs, in.truth_warp);

  if (!a.plan_match.judged)
    a.plan_match = plan_match_of(in, options, a.localization.pairs);

  // Every model, fitted and judged: not on pairs between two different buildings.
  // (The maps' own alignment judged its fit: the pairs' similarity cannot, on a bent map.)
  if (a.localization.pairs.size() > 0 &&
      (a.pairs_from == PairSource::maps || match_passes(options, a.plan_match)))
    fit_and_judge_models(in, options, a, progress);
}

}  // namespace

}  // namespace floorgrid
