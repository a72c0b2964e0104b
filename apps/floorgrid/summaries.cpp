#include "apps/floorgrid/summaries.hpp"

#include <fmt/format.h>

#include <cmath>

namespace floorgrid::app {

namespace {

std::string metres(double v) {
  return std::isfinite(v) ? fmt::format("{:.3f}", v) : "-";
}

std::string pose(const Pose2& p) {
  return fmt::format("({:.2f}, {:.2f}, {:.3f})", p.x, p.y, p.theta);
}

std::string reasons(const DivergenceCount& d) {
  if (d.total == 0)
    return "none";
  std::string text = fmt::format("{}", d.total);
  std::string sep = " (";
  for (const auto& [reason, count] : d.by_reason) {
    text += fmt::format("{}{} {}", sep, count, reason);
    sep = ", ";
  }
  return text + ")";
}

}  // namespace

void print_wall_slide(const WallSlide& s, std::size_t pairs,
                      const std::optional<ErrorStatistics>& errors_before) {
  const std::string noise =
      s.noise
          ? fmt::format("their noise between visits {:.3f} m along their walls, {:.3f} m across",
                        std::sqrt(s.noise->along_m2), std::sqrt(s.noise->across_m2))
          : std::string("no place visited twice to measure their noise along the walls");
  if (!s.applied()) {
    fmt::print("wall slide  none: {} ({} of {} pairs on a straight gridmap wall)\n", noise,
               s.pairs_on_walls, pairs);
    return;
  }
  fmt::print(
      "wall slide  {} of {} pairs on a straight gridmap wall slid along it to a smooth fit "
      "({} rounds; {}): median {:.3f} m, 95% {:.3f} m",
      s.pairs_on_walls, pairs, s.iterations, noise, s.median_slide_m, s.p95_slide_m);
  if (errors_before)
    fmt::print("; pairs' median error {:.3f} m before", errors_before->median);
  fmt::print("\n");
}

void print_localization(const DualLocalization& l,
                        const std::optional<ErrorStatistics>& pair_errors, PairSource from) {
  std::size_t usable = 0;
  for (const ScanRecord& r : l.scans)
    usable += r.pairs > 0;
  if (from == PairSource::maps && !l.scans.empty()) {
    fmt::print(
        "pairs       {} from the maps alone (the run's, from {} of {} scans, were not used: "
        "see the notes)\n",
        l.pairs.size(), usable, l.scans.size());
  }
  if (l.scans.empty()) {  // pairs from the maps alone: their story is in the notes
    fmt::print("pairs       {} from the maps alone\n", l.pairs.size());
    for (const std::string& note : l.notes)
      fmt::print("note        {}\n", note);
    if (pair_errors) {
      fmt::print("pair error  median {:.3f} m, mean {:.3f} m against the truth\n",
                 pair_errors->median, pair_errors->mean);
    }
    return;
  }
  if (from == PairSource::run)
    fmt::print("pairs       {} from {} of {} scans\n", l.pairs.size(), usable, l.scans.size());
  else if (from == PairSource::both)
    fmt::print("pairs       {} from {} of {} scans and the maps\n", l.pairs.size(), usable,
               l.scans.size());
  std::string rejected;
  for (const auto& [reason, count] : l.rejections.by_reason()) {
    if (count > 0)
      rejected += fmt::format("{}{} {}", rejected.empty() ? "" : ", ", reason, count);
  }
  fmt::print("rejected    {} beams: {}\n", l.rejections.total(),
             rejected.empty() ? "none" : rejected);
  fmt::print(
      "converged   both filters on {:.1f}% of the scans after first converging, {} periods, "
      "longest gap {} scans\n",
      100.0 * l.converged_fraction, l.converged_periods.size(), l.longest_gap);
  if (l.plan_scale_estimated) {
    fmt::print(
        "plan scale  {:.4f} +- {:.4f} world metres per plan metre (estimated; the search "
        "gave {:.4f})\n",
        l.plan_scale, l.plan_scale_std, l.plan_scale_search);
  } else {
    fmt::print("plan scale  {:.4f} (given)\n", l.plan_scale);
  }
  fmt::print("start       gridmap {} at scan {}, plan {} at scan {}\n", pose(l.start.grid),
             l.grid_start_scan, pose(l.start.plan), l.plan_start_scan);
  fmt::print("diverged    plan filter {}, gridmap filter {}\n", reasons(l.plan_divergences),
             reasons(l.grid_divergences));
  const DualLocalization::GridRestarts& restarts = l.grid_restarts;
  if (restarts.near + restarts.global > 0) {
    fmt::print(
        "restarted   gridmap filter {} times near its last pose ({} not converged there in time), "
        "{} times over the whole map\n",
        restarts.near, restarts.near_failed, restarts.global);
  }
  if (restarts.from_plan > 0) {
    fmt::print(
        "mended      gridmap filter restarted {} times where the plan filter was sure, "
        "converged on {} scans the first one was lost on\n",
        restarts.from_plan, restarts.mended_scans);
  }
  if (pair_errors) {
    fmt::print("pair error  median {} m, mean {} m, p95 {} m (against the truth)\n",
               metres(pair_errors->median), metres(pair_errors->mean), metres(pair_errors->p95));
  }
  fmt::print(
      "time        global localization {:.1f} s, scale {:.1f} s, tracking {:.1f} s, "
      "pairs {:.1f} s\n",
      l.global_localization_seconds, l.scale_search_seconds, l.localize_seconds, l.pairs_seconds);
  for (const std::string& note : l.notes)
    fmt::print("note        {}\n", note);
}

void print_models(const Alignment& a) {
  const bool truth = a.truth.has_value();
  fmt::print("\nmodel      {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>8}\n",
             truth ? "mean_m" : "", truth ? "median_m" : "", truth ? "p95_m" : "", "cv_m", "std_m",
             "walls_m", "there+back", "fit_s");
  for (const ModelAlignment& m : a.models) {
    const ModelReport& r = m.report;
    if (!r.failure.empty()) {
      fmt::print("{:<10} not fitted: {}\n", r.name, r.failure);
      continue;
    }
    const auto e = [&](double ErrorStatistics::*field) {
      return r.errors ? metres((*r.errors).*field) : std::string();
    };
    std::string std_m = "-";  // the model's stated error at a pair, where it has one
    if (r.model && r.model->error_model())
      std_m = metres(r.model->error_model()->std_at(0.0));
    fmt::print("{:<10} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>8.2f}\n", r.name,
               e(&ErrorStatistics::mean), e(&ErrorStatistics::median), e(&ErrorStatistics::p95),
               r.summary.cv_error_m ? metres(*r.summary.cv_error_m) : "-", std_m,
               metres(m.wall_distance.near_median_m), metres(r.back_and_forth.mean_m),
               r.summary.seconds);
  }
  if (truth)
    fmt::print("errors against the truth over {} domain points ({})\n",
               a.domain.points_in_plan.cols(), a.domain.kind);
  fmt::print(
      "std_m: the model's stated error at a pair, without the pairs' own noise (it grows away "
      "from the pairs; `map` gives it per point)\n");
  fmt::print(
      "walls_m: median distance of the plan's walls, mapped, to the gridmap's walls "
      "(within 2 m of a pair)\n");
  for (const ModelAlignment& m : a.models) {
    if (const auto& cv = m.report.summary.cv; cv && m.report.failure.empty()) {
      fmt::print(
          "cv_m: mean held-out error of {}-fold {} cross-validation{}{}\n", cv->folds, cv->kind,
          cv->kind == "blocked" ? fmt::format(" (whole {:.2f} m blocks held out)", cv->block_size)
                                : std::string(),
          a.wall_slide && a.wall_slide->applied()
              ? ", on the pairs before the wall slide (as std_m)"
              : "");
      break;
    }
  }
  if (!a.chosen.empty())
    fmt::print("auto chose  {}\n", a.chosen);
}

}  // namespace floorgrid::app
