#include "floorgrid/pipeline/plan_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "floorgrid/pipeline/dual_pairs.hpp"
#include "floorgrid/pipeline/filter_runner.hpp"

namespace floorgrid {

DualCheck::DualCheck(const DualCheckOptions& options, const PlanRegistration& global, double scale)
    : options_(options), global_(global), scale_(scale), local_(options.local_window, scale) {}

std::optional<PlanRestart> DualCheck::judge(std::size_t scan, ScanRecord& record) {
  const FilterRecord& plan = record.plan;
  const FilterRecord& grid = record.grid;
  const bool near = local_.fresh(scan, options_.local_min_pairs, options_.local_max_age);
  const Pose2 grid_pose = grid.matched ? grid.match.pose : grid.pose;
  const Pose2 expected = near ? local_.plan_pose(grid_pose) : global_.plan_pose(grid_pose);
  const Pose2 plan_pose = plan.matched ? plan.match.pose : plan.pose;
  // World metres (plan metres times the scale): the tolerances are about the robot and its
  // laser, whatever units or scale the plan is drawn in.
  const double off = (plan_pose.translation() - expected.translation()).norm() * scale_;
  const double turned = std::abs(normalize_angle(plan_pose.theta - expected.theta));
  if (near) {
    const double tolerance =
        options_.local_distance + options_.local_distance_growth * local_.distance_to(grid_pose);
    record.consistent = off <= tolerance && turned <= options_.local_heading;
  } else {
    record.consistent =
        off <= options_.consistency_distance && turned <= options_.consistency_heading;
  }
  // Beyond these the plan filter disagrees (the global check's are its consistency's); beyond
  // gross_factor times them, grossly.
  const double limit = near ? options_.local_reinitialize_distance : options_.consistency_distance;
  const double limit_heading =
      near ? options_.local_reinitialize_heading : options_.consistency_heading;
  const bool agrees = off <= limit && turned <= limit_heading;
  const bool gross = off > options_.gross_factor * limit ||
                     turned > std::min(std::numbers::pi, options_.gross_factor * limit_heading);
  if (plan.converged && record.consistent && plan.match.ok() && grid.match.ok())
    local_.add(scan, grid.match.pose, plan.match.pose);
  // Converged or not: a filter that flickers between converging in a wrong place and doubting
  // it is as far off as one that stays converged there; and one that hovers about the
  // tolerance, agreeing now and then, as one that disagrees throughout (an agreeing scan only
  // takes one disagreeing scan back). One that agrees but cannot converge (a place the plan
  // draws few of the walls the laser sees) is left to track.
  disagreeing_ = agrees ? std::max(0, disagreeing_ - 1) : disagreeing_ + 1;
  grossly_ = gross ? grossly_ + 1 : 0;
  unconverged_ = plan.converged ? 0 : unconverged_ + 1;
  // The plan filter declared itself lost: its own recovery would search the whole plan, where
  // a drawing of walls has look-alike places; the gridmap filter knows where the robot is.
  const bool lost =
      options_.restart_when_lost && (plan.diverged || plan.state == FilterState::recovering);
  const bool inconsistent = disagreeing_ >= options_.consistency_scans ||
                            (options_.gross_scans > 0 && grossly_ >= options_.gross_scans);
  if (!lost && !inconsistent && unconverged_ < options_.reconverge_scans)
    return std::nullopt;
  PlanRestart restart{
      .reason = lost           ? "lost"
                : inconsistent ? "inconsistent"
                               : "unconverged",
      .start = plan_start(
          expected,
          (near ? options_.local_reinitialize_sigma : options_.reinitialize_sigma) / scale_,
          near ? options_.local_reinitialize_heading_sigma : options_.reinitialize_heading_sigma,
          scale_, 0.0)};
  disagreeing_ = unconverged_ = grossly_ = 0;
  return restart;
}

TrackingStart DualCheck::gridmap_start(std::size_t scan, const Pose2& plan_pose) const {
  const bool near = local_.fresh(scan, options_.local_min_pairs, options_.local_max_age);
  return {.pose = near ? local_.map_pose(plan_pose) : global_.map_pose(plan_pose),
          .position_sigma = near ? options_.local_reinitialize_sigma : options_.reinitialize_sigma,
          .heading_sigma = near ? options_.local_reinitialize_heading_sigma
                                : options_.reinitialize_heading_sigma};
}

void DualCheck::forget_local() {
  local_.clear();
  disagreeing_ = unconverged_ = grossly_ = 0;
}

namespace {

/// The gridmap filter started where the plan filter says, while the first one is lost.
class GridmapMender {
 public:
  GridmapMender(const DualMaps& maps, const RobotLog& log, const DualLocalizerOptions& options)
      : maps_(maps), log_(log), options_(options) {}

  /// Scan `i`, with the plan filter's record already in `record`: mends record.grid when it
  /// can; `plan_was_sure` is whether the plan filter was converged on the scan before.
  void step(std::size_t i, ScanRecord& record, bool plan_was_sure, const DualCheck& check,
            DualLocalization& result) {
    if (options_.dual_check.mend_scans <= 0 || record.grid.converged) {
      runner_.reset();
      return;
    }
    if (runner_) {
      const FilterRecord r = runner_->step(i);
      if (r.converged) {
        record.grid = r;
        record.grid_mended = true;
        ++result.grid_restarts.mended_scans;
        unconverged_ = 0;
      } else if (r.diverged || ++unconverged_ >= options_.dual_check.mend_scans) {
        runner_.reset();
      }
      return;
    }
    if (!record.plan.converged || !plan_was_sure)
      return;
    const Pose2 plan_pose = record.plan.matched ? record.plan.match.pose : record.plan.pose;
    ParticleFilter filter(options_.grid.filter,
                          stream_seed(options_.seed, SeedStream::gridmap_mend, i));
    filter.initialize_tracking(check.gridmap_start(i, plan_pose), maps_.gridmap());
    runner_.emplace(std::move(filter), maps_.grid_model().model(), maps_.grid_walls(), log_,
                    maps_.grid_observation_options(), options_.grid.runner);
    runner_->start_at(i);
    unconverged_ = 0;
    ++result.grid_restarts.from_plan;
  }

 private:
  const DualMaps& maps_;
  const RobotLog& log_;
  const DualLocalizerOptions& options_;
  std::optional<FilterRunner> runner_;
  int unconverged_ = 0;
};

}  // namespace

std::vector<std::optional<Pose2>> gridmap_guide(const DualLocalization& result) {
  std::vector<std::optional<Pose2>> poses(result.scans.size());
  for (std::size_t i = 0; i < result.scans.size(); ++i) {
    if (result.scans[i].grid.converged)
      poses[i] = result.scans[i].grid.pose;
  }
  return poses;
}

void track_plan(const DualMaps& maps, const RobotLog& log, const DualLocalizerOptions& options,
                const PlanLocation& location, DualLocalization& result,
                const DualProgressCallback& progress) {
  result.plan_divergences = {};
  std::uint64_t seed = stream_seed(options.seed, SeedStream::plan_filter);
  ParticleFilter filter(options.plan.filter, seed);
  filter.initialize_tracking(plan_start(result.start.plan, location.start_sigma,
                                        location.start_heading_sigma, location.scale, 0.0),
                             maps.plan());
  FilterRunner runner(std::move(filter), maps.plan_model().model(), maps.plan_walls(), log,
                      maps.plan_observation_options(), options.plan.runner, maps.plan_rays());
  if (options.guide_plan_by_gridmap)
    runner.guide(gridmap_guide(result));
  DualCheck check(options.dual_check, location.registration, location.scale);
  SubmapCheck submap(options.dual_check.submap, log, maps.plan_model().field(), location.scale);
  std::size_t vouched = result.plan_start_scan;  // the last scan a submap check vouched for
  std::vector<double> shifts;
  GridmapMender mender(maps, log, options);
  const auto restart_plan_filter = [&](const TrackingStart& start, ScanRecord& record) {
    runner.filter() = ParticleFilter(options.plan.filter, ++seed);
    runner.filter().initialize_tracking(start, maps.plan());
    record.plan_reinitialized = true;
  };
  const std::size_t n = log.scans.size();
  std::size_t usable = 0;
  bool plan_was_sure = false;
  for (std::size_t i = result.plan_start_scan; i < n; ++i) {
    ScanRecord& record = result.scans[i];
    record.plan_reinitialized = false;
    record.consistent = true;
    record.plan = runner.step(i);
    mender.step(i, record, plan_was_sure, check, result);
    plan_was_sure = record.plan.converged;
    if (record.plan.diverged) {
      count_divergence(result.plan_divergences,
                       std::string(to_string(runner.filter().status().divergence.reason)));
    }
    if (record.grid.converged) {
      if (const std::optional<PlanRestart> restart = check.judge(i, record)) {
        if (restart->reason != "lost")  // a divergence the filter counted itself
          count_divergence(result.plan_divergences, restart->reason);
        restart_plan_filter(restart->start, record);
      }
      const Pose2 grid_pose =
          record.grid.matched && record.grid.match.ok() ? record.grid.match.pose : record.grid.pose;
      submap.add(i, grid_pose);
      if (!record.plan_reinitialized && record.plan.converged && submap.due(i)) {
        const Pose2 plan_pose = record.plan.matched ? record.plan.match.pose : record.plan.pose;
        const Pose2 registered = location.registration.plan_pose(grid_pose);
        if (const std::optional<SubmapRelocation> moved =
                submap.check(i, grid_pose, plan_pose, registered)) {
          count_divergence(result.plan_divergences, "submap");
          restart_plan_filter(
              plan_start(moved->plan_pose,
                         options.dual_check.local_reinitialize_sigma / location.scale,
                         options.dual_check.local_reinitialize_heading_sigma, location.scale, 0.0),
              record);
          check.forget_local();
          // Its poses since the last check were where the submap does not fit.
          for (std::size_t k = vouched + 1; k <= i; ++k)
            result.scans[k].consistent = false;
          shifts.push_back(moved->shift);
        }
        vouched = i;
      }
    }
    usable += usable_for_pairs(record, options.refine_poses);
    report_progress(progress, "plan", i + 1, n, record.plan.converged, usable);
  }
  if (!shifts.empty()) {
    std::sort(shifts.begin(), shifts.end());
    result.notes.push_back(fmt::format(
        "submap check: the plan filter was re-placed {} time(s), {:.2f}-{:.2f} m from where it "
        "was, where the last scans' submap fits the plan better",
        shifts.size(), shifts.front(), shifts.back()));
  }
  result.plan_corrections = runner.corrections();
  result.plan_guided_steps = runner.guided_steps();
  result.tracking_evaluations += runner.evaluations();
}

}  // namespace floorgrid
