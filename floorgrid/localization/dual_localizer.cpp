#include "floorgrid/localization/dual_localizer.hpp"

#include <chrono>
#include <cmath>
#include <memory>

#include "floorgrid/core/error.hpp"
#include "floorgrid/localization/pose_estimate.hpp"

namespace floorgrid {

ParticleFilterOptions default_plan_filter_options() {
  ParticleFilterOptions o;
  o.tracking_particles = 1000;
  o.recovery.max_augmented_fraction = 0.0;
  o.recovery.min_fast_slow_ratio = 0.0;
  o.recovery.min_beam_likelihood = 0.1;
  o.recovery.max_bad_scans = 10;
  o.convergence.min_beam_likelihood = 0.2;
  return o;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The observation model of one map, and its likelihood field (whose distance field also
/// serves the pair extraction).
struct MapModel {
  std::unique_ptr<LikelihoodFieldModel> field;
  std::unique_ptr<BeamModel> beam;
  const ObservationModel& model() const {
    return beam ? static_cast<const ObservationModel&>(*beam) : *field;
  }
  /// Global seeding scores millions of hypotheses: always the fast likelihood field.
  const ObservationModel& seeding() const { return *field; }
};

MapModel make_model(const OccupancyGrid& grid, const LikelihoodFieldOptions& field,
                    ObservationModelKind kind, const BeamModelOptions& beam) {
  MapModel m;
  m.field = std::make_unique<LikelihoodFieldModel>(grid, field);
  if (kind == ObservationModelKind::beam)
    m.beam = std::make_unique<BeamModel>(grid, beam);
  return m;
}

/// Decides when a filter takes a measurement update: after enough motion since the last one.
class UpdateGate {
 public:
  UpdateGate(double translation, double rotation)
      : translation_(translation), rotation_(rotation) {}
  /// Adds a motion; true when the filters should update now (then starts counting again).
  bool add(const OdometryMotion& m) {
    moved_ += std::abs(m.trans);
    turned_ += std::abs(m.rot1) + std::abs(m.rot2);
    if (moved_ < translation_ && turned_ < rotation_)
      return false;
    moved_ = turned_ = 0.0;
    return true;
  }

 private:
  double translation_, rotation_;
  double moved_ = 0.0, turned_ = 0.0;
};

/// One scan's step of a filter: a full step when the gate is open, a motion-only one otherwise.
void advance(ParticleFilter& filter, bool update, const OdometryMotion& motion,
             const ScanObservation& scan, const ObservationModel& model, int threads,
             std::size_t& divergences) {
  if (!update) {
    filter.predict(motion);
    return;
  }
  const FilterStatus status = filter.step(motion, scan, model, threads);
  if (status.state == FilterState::diverged)
    ++divergences;
}

/// The pose at scan 0 implied by a pose at scan k and the odometry in between (map frame; the
/// odometry's world metres divided by `scale`).
Pose2 carry_back(const Pose2& pose_k, const Pose2& odometry_0, const Pose2& odometry_k,
                 double scale) {
  const Pose2 delta = odometry_0.between(odometry_k);
  const Pose2 in_map{delta.x / scale, delta.y / scale, delta.theta};
  return pose_k.compose(in_map.inverse());
}

double path_length(const RobotLog& log, std::size_t to) {
  double length = 0.0;
  for (std::size_t i = 1; i <= to && i < log.scans.size(); ++i) {
    length +=
        (log.scans[i].robot_pose.translation() - log.scans[i - 1].robot_pose.translation()).norm();
  }
  return length;
}

/// Runs a freshly initialized filter from scan 1 until it converges; the scan index where it
/// did, or nullopt.
std::optional<std::size_t> run_until_converged(ParticleFilter& filter, const RobotLog& log,
                                               const std::vector<ScanObservation>& obs,
                                               const ObservationModel& model,
                                               const DualLocalizerOptions& o, std::size_t limit,
                                               const std::function<void(std::size_t)>& tick) {
  UpdateGate gate(o.update_min_translation, o.update_min_rotation);
  std::size_t divergences = 0;
  for (std::size_t i = 1; i < std::min(limit, obs.size()); ++i) {
    const OdometryMotion motion =
        odometry_motion(log.scans[i - 1].robot_pose, log.scans[i].robot_pose);
    advance(filter, gate.add(motion), motion, obs[i], model, o.threads, divergences);
    if (tick)
      tick(i);
    if (filter.converged())
      return i;
  }
  return std::nullopt;
}

/// Whether a scan gives pairs: both filters converged and, when poses are refined, both
/// matches accepted.
bool usable_for_pairs(const ScanRecord& r, bool refine) {
  if (!(r.plan_converged && r.grid_converged))
    return false;
  return !refine || (r.plan_match.ok() && r.grid_match.ok());
}

}  // namespace

DualLocalization localize_dual(const OccupancyGrid& plan, const OccupancyGrid& grid,
                               const RobotLog& log, const std::optional<StartPoses>& start,
                               const std::optional<double>& plan_scale,
                               const DualLocalizerOptions& o,
                               const std::function<void(const DualProgress&)>& progress,
                               const VectorFloorplan* plan_geometry) {
  if (log.scans.size() < 2)
    throw InputError("the log needs at least two laser scans", {}, 0, "log");
  if (plan_scale && !(*plan_scale > 0.0)) {
    throw InputError("must be > 0", {}, 0, "floorplan_scale");
  }
  DualLocalization result;
  const MapModel plan_model = make_model(plan, o.plan_likelihood, o.plan_model, o.beam);
  const MapModel grid_model = make_model(grid, o.grid_likelihood, o.grid_model, o.beam);
  std::vector<ScanObservation> plan_obs, grid_obs;
  plan_obs.reserve(log.scans.size());
  grid_obs.reserve(log.scans.size());
  for (const LaserScan& scan : log.scans) {
    plan_obs.push_back(make_observation(scan, o.plan_observation));
    grid_obs.push_back(make_observation(scan, o.grid_observation));
  }
  const std::size_t n = log.scans.size();
  const auto report = [&](const std::string& phase, std::size_t i, std::size_t total, bool p,
                          bool g, std::size_t pairs) {
    if (progress)
      progress({phase, i, total, p, g, pairs});
  };

  // ---- 1. global localization (and the plan's scale search) ----
  auto clock = Clock::now();
  StartPoses start_poses;
  double scale = plan_scale.value_or(1.0);
  if (start)
    start_poses = *start;
  std::optional<ScaleRange> scales;
  if (!plan_scale)
    scales = o.scale_range;
  const std::size_t global_limit = static_cast<std::size_t>(std::max(1, o.max_global_scans));
  if (!start || !plan_scale) {
    ParticleFilterOptions plan_options = o.plan_filter;
    if (scales)
      plan_options.scale_walk = o.scale_walk;
    ParticleFilter filter(plan_options, o.seed);
    if (start) {
      TrackingStart t;
      t.pose = start->plan;
      t.scale = scales ? 0.5 * (scales->min + scales->max) : scale;
      t.scale_sigma = scales ? 0.25 * (scales->max - scales->min) : 0.0;
      filter.initialize_tracking(t, plan);
    } else {
      filter.initialize_from_hypotheses(plan, plan_obs[0], plan_model.seeding(), scales, o.threads);
    }
    const auto converged_at = run_until_converged(
        filter, log, plan_obs, plan_model.model(), o, start ? n : global_limit, [&](std::size_t i) {
          report("global localization (plan)", i, global_limit, filter.converged(), false, 0);
        });
    if (!converged_at) {
      throw InputError("global localization on the floorplan did not converge within " +
                           std::to_string(global_limit) +
                           " scans (check the plan's units and "
                           "layers, or give initial_pose)",
                       {}, 0, "floorplan");
    }
    result.global_scans_plan = *converged_at;
    result.global_localization_seconds += seconds_since(clock);
    std::size_t k = *converged_at;
    if (scales) {
      // The scale search: keep tracking with scales on the particles, then take the estimates
      // of the second half of the window.
      clock = Clock::now();
      UpdateGate gate(o.update_min_translation, o.update_min_rotation);
      std::vector<double> means, variances;
      const std::size_t end = std::min(n, k + 1 + static_cast<std::size_t>(o.scale_search_scans));
      std::size_t divergences = 0;
      for (std::size_t i = k + 1; i < end; ++i) {
        const OdometryMotion motion =
            odometry_motion(log.scans[i - 1].robot_pose, log.scans[i].robot_pose);
        advance(filter, gate.add(motion), motion, plan_obs[i], plan_model.model(), o.threads,
                divergences);
        if (i >= k + 1 + (end - k - 1) / 2 && filter.converged()) {
          const PoseEstimate e = estimate_pose(filter.particles());
          means.push_back(e.scale);
          variances.push_back(e.scale_std * e.scale_std);
        }
        report("scale search", i - k, end - k - 1, filter.converged(), false, 0);
      }
      const PoseEstimate last = estimate_pose(filter.particles());
      if (means.empty()) {
        means.push_back(last.scale);
        variances.push_back(last.scale_std * last.scale_std);
        result.notes.push_back("the scale search window was too short: scale from its last scan");
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
      scale = mean;
      result.plan_scale_std = std::sqrt(within + between);
      result.plan_scale_estimated = true;
      // The pose of the scale search's last scan, carried back with the scale found.
      k = end - 1;
      if (!start) {
        start_poses.plan =
            carry_back(last.pose, log.scans[0].robot_pose, log.scans[k].robot_pose, scale);
      }
      result.scale_search_seconds = seconds_since(clock);
    } else if (!start) {
      start_poses.plan = carry_back(filter.estimate().pose, log.scans[0].robot_pose,
                                    log.scans[k].robot_pose, scale);
    }
  }
  std::size_t grid_converged_at = 0;
  if (!start) {
    clock = Clock::now();
    ParticleFilter filter(o.grid_filter, o.seed + 1);
    filter.initialize_from_hypotheses(grid, grid_obs[0], grid_model.seeding(), std::nullopt, o.threads);
    const auto converged_at = run_until_converged(
        filter, log, grid_obs, grid_model.model(), o, global_limit, [&](std::size_t i) {
          report("global localization (gridmap)", i, global_limit, true, filter.converged(), 0);
        });
    if (!converged_at) {
      throw InputError("global localization on the gridmap did not converge within " +
                           std::to_string(global_limit) + " scans (give initial_pose)",
                       {}, 0, "gridmap");
    }
    grid_converged_at = *converged_at;
    result.global_scans_grid = grid_converged_at;
    start_poses.grid = carry_back(filter.estimate().pose, log.scans[0].robot_pose,
                                  log.scans[grid_converged_at].robot_pose, 1.0);
    result.global_localization_seconds += seconds_since(clock);
  }
  result.plan_scale = scale;
  result.start = start_poses;

  // ---- 2. the localizing pass: both filters tracked from the start, pairs where both agree ----
  clock = Clock::now();
  const auto start_sigma = [&](std::size_t k, double map_scale) {
    const double travelled = path_length(log, k) / map_scale;
    return std::pair<double, double>{std::min(2.0, 0.2 + 0.03 * travelled),
                                     std::min(0.5, 0.05 + 0.01 * travelled)};
  };
  ParticleFilter plan_filter(o.plan_filter, o.seed + 2);
  ParticleFilter grid_filter(o.grid_filter, o.seed + 3);
  {
    TrackingStart t;
    t.pose = start_poses.plan;
    std::tie(t.position_sigma, t.heading_sigma) =
        start ? std::pair<double, double>{0.2, 0.1} : start_sigma(result.global_scans_plan, scale);
    t.scale = scale;
    plan_filter.initialize_tracking(t, plan);
    TrackingStart g;
    g.pose = start_poses.grid;
    std::tie(g.position_sigma, g.heading_sigma) =
        start ? std::pair<double, double>{0.2, 0.1} : start_sigma(grid_converged_at, 1.0);
    grid_filter.initialize_tracking(g, grid);
  }
  UpdateGate gate(o.update_min_translation, o.update_min_rotation);
  const WallField plan_walls =
      plan_geometry ? WallField(*plan_geometry, plan.geometry(), o.walls) : WallField(plan, o.walls);
  const WallField grid_walls(grid, o.walls);
  std::size_t usable = 0;  // scans that will give pairs so far
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      const OdometryMotion motion =
          odometry_motion(log.scans[i - 1].robot_pose, log.scans[i].robot_pose);
      const bool update = gate.add(motion);
      advance(plan_filter, update, motion, plan_obs[i], plan_model.model(), o.threads,
              result.plan_divergences);
      advance(grid_filter, update, motion, grid_obs[i], grid_model.model(), o.threads,
              result.grid_divergences);
    } else {
      plan_filter.step({}, plan_obs[0], plan_model.model(), o.threads);
      grid_filter.step({}, grid_obs[0], grid_model.model(), o.threads);
    }
    ScanRecord record;
    record.scan = i;
    record.plan_state = plan_filter.state();
    record.grid_state = grid_filter.state();
    record.plan_converged = plan_filter.converged();
    record.grid_converged = grid_filter.converged();
    record.plan_check = plan_filter.status().convergence;
    record.grid_check = grid_filter.status().convergence;
    record.plan_fit = plan_filter.status().mean_beam_likelihood;
    record.grid_fit = grid_filter.status().mean_beam_likelihood;
    record.plan_pose = estimate_pose(plan_filter.particles()).pose;
    record.grid_pose = estimate_pose(grid_filter.particles()).pose;
    if (o.refine_poses && record.plan_converged && record.grid_converged) {
      const ScanObservation points = make_observation(log.scans[i], o.match_observation);
      record.plan_match = match_scan(plan_walls, points, record.plan_pose, scale, o.plan_match);
      record.grid_match = match_scan(grid_walls, points, record.grid_pose, 1.0, o.grid_match);
    }
    usable += usable_for_pairs(record, o.refine_poses);
    result.scans.push_back(record);
    if (i % 25 == 0 || i + 1 == n)
      report("localize", i + 1, n, record.plan_converged, record.grid_converged, usable);
  }
  result.localize_seconds = seconds_since(clock);

  // ---- 3. the plan's scale refitted with the refined poses of every usable scan ----
  if (result.plan_scale_estimated && o.refine_poses && o.refit_scale) {
    clock = Clock::now();
    std::vector<ScanObservation> points;
    std::vector<Pose2> poses;
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < result.scans.size(); ++k) {
      if (!usable_for_pairs(result.scans[k], true))
        continue;
      points.push_back(make_observation(log.scans[k], o.match_observation));
      poses.push_back(result.scans[k].plan_match.pose);
      which.push_back(k);
    }
    if (points.size() >= 10) {
      std::vector<const ScanObservation*> views;
      for (const ScanObservation& p : points)
        views.push_back(&p);
      const ScaleFit fit = fit_scale(plan_walls, views, poses, scale, o.plan_match);
      result.plan_scale_search = scale;
      result.plan_scale_search_std = result.plan_scale_std;
      scale = fit.scale;
      result.plan_scale = fit.scale;
      result.plan_scale_std = fit.scale_std;
      for (std::size_t k = 0; k < which.size(); ++k)
        result.scans[which[k]].plan_match.pose = fit.poses[k];
      result.notes.push_back("plan scale refitted on " + std::to_string(fit.scans) +
                             " scans by joint scan matching");
    } else {
      result.notes.push_back("too few matched scans to refit the plan scale: kept the search's");
    }
    result.scale_search_seconds += seconds_since(clock);
  }

  // ---- 4. pairs from every usable scan ----
  clock = Clock::now();
  PairCollector pairs;
  for (ScanRecord& record : result.scans) {
    const LaserScan& scan = log.scans[record.scan];
    if (!(record.plan_converged && record.grid_converged)) {
      reject_scan(scan, result.rejections);
      continue;
    }
    Pose2 plan_pose = record.plan_pose, grid_pose = record.grid_pose;
    if (o.refine_poses) {
      const ScanMatchFailure failure = record.plan_match.ok() ? record.grid_match.failure
                                                              : record.plan_match.failure;
      if (failure == ScanMatchFailure::degenerate) {
        result.rejections.degenerate += scan.ranges.size();
        continue;
      }
      if (failure != ScanMatchFailure::none) {
        result.rejections.unmatched += scan.ranges.size();
        continue;
      }
      plan_pose = record.plan_match.pose;
      grid_pose = record.grid_match.pose;
    }
    const std::size_t before = pairs.size();
    extract_scan_pairs(scan, plan_pose, scale, grid_pose, plan_walls, grid_walls, o.pairs,
                       pairs, result.rejections);
    record.pairs = pairs.size() - before;
  }
  result.pairs = pairs.pairs();
  result.pairs_seconds = seconds_since(clock);
  result.plan_scale = scale;

  // Convergence bookkeeping.
  std::optional<std::size_t> first;
  std::size_t both = 0;
  for (const ScanRecord& r : result.scans) {
    const bool ok = r.plan_converged && r.grid_converged;
    if (ok && !first)
      first = r.scan;
    if (first && ok)
      ++both;
    if (ok) {
      if (!result.converged_periods.empty() &&
          result.converged_periods.back().second + 1 == r.scan) {
        result.converged_periods.back().second = r.scan;
      } else {
        result.converged_periods.emplace_back(r.scan, r.scan);
      }
    }
  }
  if (first)
    result.converged_fraction = static_cast<double>(both) / static_cast<double>(n - *first);
  if (!first)
    result.notes.push_back("the two filters were never converged at the same time: no pairs");
  return result;
}

}  // namespace floorgrid
