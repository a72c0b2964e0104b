#include "floorgrid/pipeline/dual_localizer.hpp"

#include <chrono>
#include <cmath>
#include <memory>

#include "floorgrid/core/error.hpp"
#include "floorgrid/pipeline/dual_pairs.hpp"

namespace floorgrid {

ParticleFilterOptions default_plan_filter_options() {
  ParticleFilterOptions o;
  o.recovery.max_augmented_fraction = 0.0;
  o.recovery.min_fast_slow_ratio = 0.0;
  o.recovery.min_beam_likelihood = 0.1;
  o.recovery.max_bad_scans = 10;
  o.convergence.min_beam_likelihood = 0.2;
  o.convergence.min_ess_ratio = 0.01;
  return o;
}

ParticleFilterOptions default_grid_filter_options() {
  ParticleFilterOptions o;
  o.recovery.max_augmented_fraction = 0.0;
  o.recovery.min_fast_slow_ratio = 0.0;
  o.convergence.min_ess_ratio = 0.01;
  // The gridmap holds what the laser sees: a filter in the right place explains most of a
  // scan (about 0.9 of the mean beam likelihood), one in a look-alike place far less.
  o.convergence.min_beam_likelihood = 0.5;
  o.recovery.min_beam_likelihood = 0.35;
  return o;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The observation model of one map: the likelihood field always (global seeding scores
/// millions of hypotheses with it), and the beam model when chosen.
struct MapModel {
  std::unique_ptr<LikelihoodFieldModel> field;
  std::unique_ptr<BeamModel> beam;
  const ObservationModel& model() const {
    return beam ? static_cast<const ObservationModel&>(*beam) : *field;
  }
};

MapModel make_model(const OccupancyGrid& grid, const LikelihoodFieldOptions& field,
                    ObservationModelKind kind, const BeamModelOptions& beam) {
  MapModel m;
  m.field = std::make_unique<LikelihoodFieldModel>(grid, field);
  if (kind == ObservationModelKind::beam)
    m.beam = std::make_unique<BeamModel>(grid, beam);
  return m;
}

void count_divergence(DivergenceCount& count, const std::string& reason) {
  ++count.total;
  ++count.by_reason[reason];
}

/// The plan filter's first cloud: around `pose`, with the scale fixed or spread for a search.
TrackingStart plan_start(const Pose2& pose, double position_sigma, double heading_sigma,
                         double scale, double scale_sigma) {
  TrackingStart t;
  t.pose = pose;
  t.position_sigma = position_sigma;
  t.heading_sigma = heading_sigma;
  t.scale = scale;
  t.scale_sigma = scale_sigma;
  return t;
}

/// The scale search: the plan filter tracks `scans` scans from `first` with scales on its
/// particles; the mean and spread of its estimates over the second half of the window. The
/// converged scans' poses are added to `poses` (scan index, pose).
std::pair<double, double> search_scale(FilterRunner& runner, std::size_t first, std::size_t scans,
                                       std::size_t n, std::vector<std::string>& notes,
                                       std::vector<std::pair<std::size_t, Pose2>>& poses) {
  std::vector<double> means, variances;
  const std::size_t end = std::min(n, first + scans);
  for (std::size_t i = first; i < end; ++i) {
    const FilterRecord r = runner.step(i);
    if (r.converged)
      poses.emplace_back(i, r.pose);
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
        "the plan filter did not converge during the scale search: scale from its "
        "last scan");
  }
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

}  // namespace

DualLocalization localize_dual(const OccupancyGrid& drawn_plan, const OccupancyGrid& grid,
                               const RobotLog& log, const std::optional<StartPoses>& start,
                               const std::optional<double>& plan_scale,
                               const DualLocalizerOptions& o,
                               const std::function<void(const DualProgress&)>& progress,
                               const VectorFloorplan* plan_geometry) {
  if (log.scans.size() < 2)
    throw InputError("the log needs at least two laser scans", {}, 0, "log");
  if (plan_scale && !(*plan_scale > 0.0 && std::isfinite(*plan_scale)))
    throw InputError("must be a number > 0 or auto", {}, 0, "floorplan_scale");
  validate(o.scale_range);
  const std::size_t n = log.scans.size();
  DualLocalization result;
  result.scans.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    result.scans[i].scan = i;
  const auto report = [&](const char* phase, std::size_t i, std::size_t total, bool converged,
                          std::size_t pairs = 0) {
    if (progress && (i % 25 == 0 || i == total))
      progress({phase, i, total, converged, pairs});
  };

  auto clock = Clock::now();
  // The plan as a robot inside sees it (the unseen faces of walls drawn as two lines dropped).
  VisibleWalls visible;
  if (o.visible_walls_only)
    visible = visible_walls(drawn_plan, o.visible);
  const OccupancyGrid& plan = visible.applied ? visible.grid : drawn_plan;
  if (o.visible_walls_only && !visible.applied)
    result.notes.push_back("the plan has no closed inside: every drawn wall is used");
  const MapModel plan_model = make_model(plan, o.plan_likelihood, o.plan_model, o.beam);
  const MapModel grid_model = make_model(grid, o.grid_likelihood, o.grid_model, o.beam);
  const WallField plan_walls =
      plan_geometry ? WallField(*plan_geometry, plan.geometry(), o.walls,
                                visible.applied ? &visible.grid : nullptr,
                                visible.applied ? &visible.room : nullptr)
                    : WallField(plan, o.walls, visible.applied ? &visible.room : nullptr);
  const WallField grid_walls(grid, o.walls);
  std::optional<GridRayCaster> plan_caster;
  if (o.plan_beam_consistency)
    plan_caster.emplace(plan);
  const GridRayCaster* plan_rays = plan_caster ? &*plan_caster : nullptr;
  std::vector<ScanObservation> plan_obs, grid_obs;
  plan_obs.reserve(n);
  grid_obs.reserve(n);
  for (const LaserScan& scan : log.scans) {
    plan_obs.push_back(make_observation(scan, o.plan_observation));
    grid_obs.push_back(make_observation(scan, o.grid_observation));
  }

  // ---- 1. the gridmap filter: global localization (or the given start), then tracking ----
  bool start_held = start.has_value();  // the given start: did the gridmap filter keep to it?
  {
    ParticleFilter filter(o.grid_filter, o.seed + 1);
    if (start) {
      TrackingStart t;
      t.pose = start->grid;
      filter.initialize_tracking(t, grid);
    } else {
      filter.initialize_from_hypotheses(grid, grid_obs[0], *grid_model.field, std::nullopt,
                                        o.threads);
    }
    FilterRunner runner(std::move(filter), grid_model.model(), grid_walls, log, grid_obs,
                        o.grid_runner);
    if (!start)
      runner.start_at(0);
    std::optional<std::size_t> first_converged;
    for (std::size_t i = start ? 0 : 1; i < n; ++i) {
      FilterRecord& r = result.scans[i].grid = runner.step(i);
      if (r.diverged) {
        count_divergence(result.grid_divergences,
                         std::string(to_string(runner.filter().status().divergence.reason)));
        start_held = start_held && first_converged.has_value();
        // Lost on the gridmap: localize globally again from this scan's best hypotheses (far
        // more reliable than waiting for the recovery's injected particles to find the place).
        runner.filter() = ParticleFilter(o.grid_filter, o.seed + 1000 + i);
        runner.filter().initialize_from_hypotheses(grid, grid_obs[i], *grid_model.field,
                                                   std::nullopt, o.threads);
        r.state = FilterState::global;
        r.converged = false;
      }
      if (r.converged && !first_converged) {
        first_converged = i;
        if (!start)
          result.global_localization_seconds = seconds_since(clock);
      }
      if (!first_converged && i >= static_cast<std::size_t>(std::max(1, o.max_global_scans))) {
        throw InputError("global localization on the gridmap did not converge within " +
                             std::to_string(o.max_global_scans) +
                             " scans (check the map's resolution and origin, or give "
                             "initial_pose)",
                         {}, 0, "gridmap");
      }
      report("gridmap", i + 1, n, r.converged);
    }
    if (!first_converged)
      throw InputError("the gridmap filter never converged", {}, 0, "gridmap");
    result.grid_start_scan = *first_converged;
    result.grid_corrections = runner.corrections();
    result.tracking_evaluations += runner.evaluations();
  }
  result.grid_seconds = seconds_since(clock);
  result.localize_seconds += result.grid_seconds - result.global_localization_seconds;
  // A given start the gridmap filter had to abandon says nothing about the plan either: the
  // plan is then located like without a start.
  if (start && !start_held) {
    result.notes.push_back(
        "the gridmap filter diverged from the given start before converging: "
        "initial_pose ignored, the plan located by registering the run");
  }
  const std::optional<StartPoses> given = start_held ? start : std::nullopt;
  const Pose2 grid_start = given ? given->grid : result.scans[result.grid_start_scan].grid.pose;

  // ---- 2. where the run lies on the plan ----
  clock = Clock::now();
  const std::optional<ScaleRange> scales =
      plan_scale ? std::nullopt : std::optional<ScaleRange>(o.scale_range);
  PlanRegistration registration;
  double scale = plan_scale.value_or(0.5 * (o.scale_range.min + o.scale_range.max));
  double scale_sigma = plan_scale ? 0.0 : 0.25 * (o.scale_range.max - o.scale_range.min);
  if (given) {
    registration = PlanRegistration(given->grid, given->plan, scale);
  } else {
    // The endpoints of every scan the gridmap filter was sure of, as one submap.
    std::vector<std::size_t> scans;
    std::vector<Pose2> poses;
    for (const ScanRecord& r : result.scans) {
      if (r.grid.converged && (!r.grid.matched || r.grid.match.ok())) {
        scans.push_back(r.scan);
        poses.push_back(r.grid.matched ? r.grid.match.pose : r.grid.pose);
      }
    }
    const ScanObservation submap = build_submap(log, scans, poses, grid_start, o.submap);
    const LikelihoodFieldModel wide(plan, o.registration_likelihood);
    result.registration =
        register_on_plan(plan, wide, submap, grid_start, scales, scale, o.registration, o.threads);
    registration = result.registration->registration;
    if (!plan_scale) {
      scale = registration.scale();
      const double step =
          (o.scale_range.max - o.scale_range.min) / std::max(1, o.registration.seeding.scales);
      scale_sigma = step;
    }
    result.plan_start_scan = result.grid_start_scan;
  }
  result.global_localization_seconds += seconds_since(clock);
  result.start.grid = grid_start;
  result.start.plan = given ? given->plan : registration.plan_pose(grid_start);
  const double start_sigma = given ? 0.2 : o.reinitialize_sigma;
  const double start_heading_sigma = given ? 0.1 : o.reinitialize_heading_sigma;

  // ---- 3. the plan's scale searched by the plan filter ----
  if (!plan_scale) {
    clock = Clock::now();
    ParticleFilterOptions options = o.plan_filter;
    options.scale_walk = o.scale_walk;
    ParticleFilter filter(options, o.seed + 2);
    filter.initialize_tracking(
        plan_start(result.start.plan, start_sigma, start_heading_sigma, scale, scale_sigma), plan);
    FilterRunnerOptions runner_options = o.plan_runner;
    runner_options.improved_proposal = false;  // the proposal would match at the mean scale
    runner_options.refine = false;
    const MapModel search_model = make_model(plan, o.plan_likelihood, o.scale_search_model, o.beam);
    std::vector<ScanObservation> search_obs;
    search_obs.reserve(n);
    for (const LaserScan& scan : log.scans)
      search_obs.push_back(make_observation(scan, o.scale_search_observation));
    FilterRunner runner(std::move(filter), search_model.model(), plan_walls, log, search_obs,
                        runner_options);
    std::vector<std::pair<std::size_t, Pose2>> searched;
    std::tie(scale, result.plan_scale_std) = search_scale(
        runner, result.plan_start_scan, static_cast<std::size_t>(std::max(1, o.scale_search_scans)),
        n, result.notes, searched);
    // The profile: which scale puts the most endpoints exactly on the plan's walls.
    if (!searched.empty() && o.scale_profile_steps > 0) {
      std::vector<ScanObservation> points;
      std::vector<Pose2> poses;
      const std::size_t count =
          std::min(searched.size(), std::max<std::size_t>(1, o.scale_profile_scans));
      for (std::size_t k = 0; k < count; ++k) {
        const auto& [scan, pose] = searched[k * searched.size() / count];
        points.push_back(make_observation(log.scans[scan], o.plan_runner.match_observation));
        poses.push_back(pose);
      }
      std::vector<const ScanObservation*> views;
      for (const ScanObservation& p : points)
        views.push_back(&p);
      std::vector<double> candidates;
      for (int k = -o.scale_profile_steps; k <= o.scale_profile_steps; ++k)
        candidates.push_back(scale * (1.0 + o.scale_profile_range * k / o.scale_profile_steps));
      const ScaleProfile profile =
          profile_scale(plan_walls, views, poses, candidates, o.plan_runner.match, plan_rays,
                        o.plan_runner.beam_tolerance);
      if (std::abs(profile.best / scale - 1.0) > 1e-9)
        result.notes.push_back("the scale search gave " + std::to_string(scale) +
                               ", the profile of matched scans " + std::to_string(profile.best));
      scale = profile.best;
    }
    result.plan_scale_search = scale;
    result.plan_scale_search_std = result.plan_scale_std;
    result.plan_scale_estimated = true;
    if (given)
      registration = PlanRegistration(given->grid, given->plan, scale);
    result.scale_search_seconds = seconds_since(clock);
  }

  // ---- 4. the plan filter tracks, checked against the gridmap filter ----
  const auto track_plan = [&](double track_scale) {
    result.plan_divergences = {};
    std::uint64_t seed = o.seed + 3;
    ParticleFilter filter(o.plan_filter, seed);
    filter.initialize_tracking(
        plan_start(result.start.plan, start_sigma, start_heading_sigma, track_scale, 0.0), plan);
    FilterRunner runner(std::move(filter), plan_model.model(), plan_walls, log, plan_obs,
                        o.plan_runner, plan_rays);
    int disagreeing = 0, unconverged = 0;
    std::size_t usable = 0;
    LocalRegistration local(o.local_window, track_scale);
    for (std::size_t i = result.plan_start_scan; i < n; ++i) {
      ScanRecord& record = result.scans[i];
      record.plan_reinitialized = false;
      record.consistent = true;
      FilterRecord& r = record.plan = runner.step(i);
      if (r.diverged)
        count_divergence(result.plan_divergences,
                         std::string(to_string(runner.filter().status().divergence.reason)));
      if (record.grid.converged) {
        const bool near = local.fresh(i, o.local_min_pairs, o.local_max_age);
        const Pose2 grid_pose = record.grid.matched ? record.grid.match.pose : record.grid.pose;
        const Pose2 expected =
            near ? local.plan_pose(grid_pose) : registration.plan_pose(grid_pose);
        const Pose2 plan_pose = r.matched ? r.match.pose : r.pose;
        const double off = (plan_pose.translation() - expected.translation()).norm();
        const double turned = std::abs(normalize_angle(plan_pose.theta - expected.theta));
        record.consistent = near ? off <= o.local_distance && turned <= o.local_heading
                                 : off <= o.consistency_distance && turned <= o.consistency_heading;
        const bool agrees =
            near ? off <= o.local_reinitialize_distance && turned <= o.local_reinitialize_heading
                 : record.consistent;
        if (r.converged && record.consistent && r.match.ok() && record.grid.match.ok())
          local.add(i, record.grid.match.pose, r.match.pose);
        disagreeing = r.converged && !agrees ? disagreeing + 1 : 0;
        unconverged = r.converged ? 0 : unconverged + 1;
        if (disagreeing >= o.consistency_scans || unconverged >= o.reconverge_scans) {
          count_divergence(result.plan_divergences,
                           disagreeing >= o.consistency_scans ? "inconsistent" : "unconverged");
          runner.filter() = ParticleFilter(o.plan_filter, ++seed);
          runner.filter().initialize_tracking(
              plan_start(expected, near ? 0.3 : o.reinitialize_sigma,
                         near ? 0.1 : o.reinitialize_heading_sigma, track_scale, 0.0),
              plan);
          record.plan_reinitialized = true;
          disagreeing = unconverged = 0;
        }
      }
      usable += usable_for_pairs(record, o.refine_poses);
      report("plan", i + 1, n, r.converged, usable);
    }
    result.plan_corrections = runner.corrections();
    result.tracking_evaluations += runner.evaluations();
  };

  // ---- 5. the scale refitted with the refined plan poses; tracked again when it moved ----
  for (int pass = 1;; ++pass) {
    clock = Clock::now();
    track_plan(scale);
    result.localize_seconds += seconds_since(clock);
    if (!(result.plan_scale_estimated && o.refine_poses && o.refit_scale))
      break;
    clock = Clock::now();
    const double refit = refit_plan_scale(result, log, plan_walls, o.plan_runner, scale, plan_rays);
    result.scale_search_seconds += seconds_since(clock);
    // A refit far from the search (too few or bad scans) is not trusted.
    if (std::abs(refit / scale - 1.0) > 0.1) {
      result.plan_scale_std = result.plan_scale_search_std;
      result.notes.push_back("the scale refit went far from the search's: kept the search's");
      break;
    }
    const bool moved = std::abs(refit / scale - 1.0) > o.retrack_scale_change;
    scale = refit;
    if (given)
      registration = PlanRegistration(given->grid, given->plan, scale);
    if (!moved || pass >= o.max_plan_passes)
      break;
    result.notes.push_back("the plan tracked again with the refitted scale");
  }
  result.plan_scale = scale;
  clock = Clock::now();
  make_pairs(result, log, plan_walls, grid_walls, o.pairs, o.refine_poses);
  drop_outlier_scans(result, o.outlier_scans);
  result.pairs_seconds = seconds_since(clock);
  summarize_convergence(result);
  return result;
}

}  // namespace floorgrid
