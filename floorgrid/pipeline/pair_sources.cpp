#include "floorgrid/pipeline/pair_sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "floorgrid/core/statistics.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/point_index.hpp"

namespace floorgrid {

void validate(const PairSourceOptions& o, const std::string& prefix) {
  const auto positive = [&](double value, const char* field) {
    require_option(value > 0.0 && std::isfinite(value), prefix + field, value, "> 0");
  };
  positive(o.coverage_radius, "coverage_radius");
  require_option(o.min_coverage >= 0.0 && o.min_coverage <= 1.0, prefix + "min_coverage",
                 o.min_coverage, "in 0..1");
  require_option(o.min_pair_scan_share >= 0.0 && o.min_pair_scan_share <= 1.0,
                 prefix + "min_pair_scan_share", o.min_pair_scan_share, "in 0..1");
  require_option(o.min_converged_share >= 0.0 && o.min_converged_share <= 1.0,
                 prefix + "min_converged_share", o.min_converged_share, "in 0..1");
  positive(o.disagreement_sigmas, "disagreement_sigmas");
  positive(o.bias_cell, "bias_cell");
  require_option(o.min_disagreement_tolerance >= 0.0 && std::isfinite(o.min_disagreement_tolerance),
                 prefix + "min_disagreement_tolerance", o.min_disagreement_tolerance, ">= 0");
  positive(o.scale_sigmas, "scale_sigmas");
  require_option(o.min_scale_tolerance >= 0.0 && o.min_scale_tolerance < 1.0,
                 prefix + "min_scale_tolerance", o.min_scale_tolerance, "in [0, 1)");
  require_option(o.fill_radius >= 0.0 && std::isfinite(o.fill_radius), prefix + "fill_radius",
                 o.fill_radius, ">= 0");
  require_option(o.run_match_margin >= -1.0 && o.run_match_margin <= 1.0,
                 prefix + "run_match_margin", o.run_match_margin, "in [-1, 1]");
}

double wall_coverage(const OccupancyGrid& gridmap, const Eigen::Matrix2Xd& points_in_grid,
                     double radius) {
  // One point per quarter of the radius is as good as all of them for "within the radius".
  const double bin = 0.25 * radius;
  std::set<std::pair<long, long>> taken;
  std::vector<Eigen::Vector2d> kept;
  for (Eigen::Index i = 0; i < points_in_grid.cols(); ++i) {
    const Eigen::Vector2d p = points_in_grid.col(i);
    if (taken.emplace(std::lround(std::floor(p.x() / bin)), std::lround(std::floor(p.y() / bin)))
            .second)
      kept.push_back(p);
  }
  Eigen::Matrix2Xd thinned(2, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i)
    thinned.col(static_cast<Eigen::Index>(i)) = kept[i];
  const PointIndex2D index(thinned);
  std::size_t walls = 0, covered = 0;
  for (int iy = 0; iy < gridmap.height(); ++iy) {
    for (int ix = 0; ix < gridmap.width(); ++ix) {
      if (gridmap.state(ix, iy) != CellState::occupied)
        continue;
      ++walls;
      if (index.size() > 0 &&
          index.nearest(gridmap.geometry().cell_center(ix, iy)).distance <= radius)
        ++covered;
    }
  }
  return walls > 0 ? static_cast<double>(covered) / static_cast<double>(walls) : 0.0;
}

ReferencePairs pairs_beyond(const ReferencePairs& maps, const Eigen::Matrix2Xd& points_in_grid,
                            double radius) {
  const PointIndex2D index(points_in_grid);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < maps.size(); ++i) {
    if (index.size() == 0 || index.nearest(maps.points_in_grid.col(i)).distance > radius)
      kept.push_back(i);
  }
  ReferencePairs out;
  out.points_in_plan.resize(2, static_cast<Eigen::Index>(kept.size()));
  out.points_in_grid.resize(2, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    out.points_in_plan.col(static_cast<Eigen::Index>(k)) = maps.points_in_plan.col(kept[k]);
    out.points_in_grid.col(static_cast<Eigen::Index>(k)) = maps.points_in_grid.col(kept[k]);
  }
  return out;
}

double radius_of_gyration(const Eigen::Matrix2Xd& points) {
  if (points.cols() == 0)
    return 0.0;
  const Eigen::Vector2d centre = points.rowwise().mean();
  return std::sqrt((points.colwise() - centre).colwise().squaredNorm().mean());
}

namespace {

// The run judged on its own: it made pairs, they pass the plan-match check, and they come from
// enough scans covering enough of the gridmap's walls.
void judge_run(const RunPairsSummary& run, const OccupancyGrid& gridmap, const PairSourceOptions& o,
               PairSourceCheck& c) {
  c.run_localized = run.localized && run.pairs && run.pairs->size() >= 3;
  c.scans = run.scans;
  c.pair_scans = run.pair_scans;
  c.run_match = run.match;
  if (!c.run_localized) {
    c.run_failure = run.failure.empty() ? "the run made no pairs" : run.failure;
    return;
  }
  c.coverage = wall_coverage(gridmap, run.pairs->points_in_grid, o.coverage_radius);
  const std::size_t needed_scans = std::min(
      o.min_pair_scans,
      static_cast<std::size_t>(std::ceil(o.min_pair_scan_share * static_cast<double>(run.scans))));
  if (!run.match_accepted) {
    c.run_failure = fmt::format(
        "the plan does not match the gridmap under the run's pairs (plan match {:.2f}, {:.0f}% "
        "of the plan's walls in space the robot saw free)",
        run.match.score.score, 100.0 * run.match.score.in_free_space);
  } else if (run.converged_fraction < o.min_converged_share) {
    c.run_failure = fmt::format(
        "both filters were converged on {:.0f}% of the scans (at least {:.0f}% needed): the log "
        "does not fit the gridmap for most of the run (is the gridmap's resolution right?)",
        100.0 * run.converged_fraction, 100.0 * o.min_converged_share);
  } else if (c.pair_scans < needed_scans) {
    c.run_failure = fmt::format(
        "the run's pairs come from {} of {} scans (at least {} needed): a few scans agree with "
        "themselves wherever they are",
        c.pair_scans, c.scans, needed_scans);
  } else if (c.coverage < o.min_coverage) {
    c.run_failure = fmt::format(
        "the run's pairs cover {:.0f}% of the gridmap's walls (within {:.1f} m; at least {:.0f}% "
        "needed)",
        100.0 * c.coverage, o.coverage_radius, 100.0 * o.min_coverage);
  }
  c.run_accepted = c.run_failure.empty();
}

// The run's pairs against the maps' bent map: where it puts each pair's grid point on the plan,
// against the pair's plan point (world metres), and the two scales.
void compare_with_maps(const RunPairsSummary& run, const MapAlignment& maps,
                       const PairSourceOptions& o, PairSourceCheck& c) {
  const ReferencePairs& pairs = *run.pairs;
  const double placed = maps.scale.relative_std * radius_of_gyration(pairs.points_in_grid);
  c.disagreement_tolerance_m =
      std::max(o.min_disagreement_tolerance,
               o.disagreement_sigmas * std::sqrt(placed * placed + run.noise_m * run.noise_m));
  std::vector<double> distances;
  // Per cell of bias_cell metres: the sum of the disagreement vectors and their count.
  std::map<std::pair<long, long>, std::pair<Eigen::Vector2d, int>> cells;
  std::vector<std::pair<long, long>> cell_of;
  // At most about 20,000 pairs, evenly: plenty for a median.
  const Eigen::Index step = std::max<Eigen::Index>(1, pairs.size() / 20000);
  for (Eigen::Index i = 0; i < pairs.size(); i += step) {
    const Eigen::Vector2d grid = pairs.points_in_grid.col(i);
    const Eigen::Vector2d mapped = maps.warp->apply(grid);
    const Eigen::Vector2d apart = (mapped - pairs.points_in_plan.col(i)) * run.plan_scale;
    distances.push_back(apart.norm());
    const std::pair<long, long> cell{std::lround(std::floor(grid.x() / o.bias_cell)),
                                     std::lround(std::floor(grid.y() / o.bias_cell))};
    auto& [sum, count] = cells.try_emplace(cell, Eigen::Vector2d::Zero(), 0).first->second;
    sum += apart;
    ++count;
    cell_of.push_back(cell);
  }
  std::vector<double> shared;
  shared.reserve(cell_of.size());
  for (const std::pair<long, long>& cell : cell_of) {
    const auto& [sum, count] = cells.at(cell);
    shared.push_back(sum.norm() / count);
  }
  c.compared = true;
  c.disagreement_median_m = median(distances);
  c.disagreement_p90_m = quantile(distances, 0.9);
  c.disagreement_local_median_m = median(shared);
  c.run_scale = run.plan_scale;
  c.maps_scale = maps.scale.scale;
  c.run_scale_at_drawn_walls = run.scale_at_drawn_walls;
  const double faces =
      run.scale_at_drawn_walls > 0.0 ? std::abs(c.run_scale - run.scale_at_drawn_walls) : 0.0;
  c.scale_tolerance =
      c.maps_scale * std::max(o.min_scale_tolerance, o.scale_sigmas * maps.scale.relative_std) +
      faces;
  c.agree = c.disagreement_median_m <= c.disagreement_tolerance_m &&
            std::abs(c.run_scale - c.maps_scale) <= c.scale_tolerance;
}

}  // namespace

PairSourceCheck check_pair_sources(const RunPairsSummary& run, const MapAlignment* maps,
                                   const OccupancyGrid& gridmap, const PairSourceOptions& o,
                                   const std::function<PlanMatch(const ReferencePairs&)>& judge,
                                   const std::function<bool(const PlanMatch&)>& accepts) {
  const auto maps_pass = [&](const PlanMatch& m) { return !accepts || accepts(m); };
  PairSourceCheck c;
  judge_run(run, gridmap, o, c);
  c.maps_accepted = maps && maps->accepted && maps->warp;
  if (c.run_accepted && c.maps_accepted) {
    compare_with_maps(run, *maps, o, c);
    if (c.agree) {
      c.chosen = "run";
      if (o.fill_radius > 0.0)
        c.fill = pairs_beyond(maps->pairs, run.pairs->points_in_grid, o.fill_radius);
      return c;
    }
    // They disagree: the plan-match check, the same measure for both, says which to trust.
    c.maps_match = judge(maps->pairs);
    if (c.maps_match.judged && c.run_match.judged && maps_pass(c.maps_match) &&
        c.run_match.score.score <= c.maps_match.score.score + o.run_match_margin) {
      c.chosen = "maps";
      c.fallback = fmt::format(
          "the run's pairs disagree with the maps' alignment ({:.2f} m apart at the median, "
          "scales {:.4f} and {:.4f}) and the plan-match check does not prefer the run's ({:.2f} "
          "against the maps' {:.2f})",
          c.disagreement_median_m, c.run_scale, c.maps_scale, c.run_match.score.score,
          c.maps_match.score.score);
    } else {
      c.chosen = "run";
    }
    return c;
  }
  if (c.run_accepted) {
    c.chosen = "run";
  } else if (c.maps_accepted) {
    c.maps_match = judge(maps->pairs);
    if (maps_pass(c.maps_match)) {
      c.chosen = "maps";
      c.fallback = c.run_failure;
    } else {
      c.maps_failure = fmt::format(
          "the plan does not match the gridmap under the maps' pairs either (plan match {:.2f}, "
          "{:.0f}% of the plan's walls in space the robot saw free)",
          c.maps_match.score.score, 100.0 * c.maps_match.score.in_free_space);
    }
  }
  return c;
}

}  // namespace floorgrid
