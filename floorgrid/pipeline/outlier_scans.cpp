#include "floorgrid/pipeline/outlier_scans.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/ransac.hpp"
#include "floorgrid/localization/pair_extraction.hpp"

namespace floorgrid {

namespace {

using Cells = std::map<std::pair<long, long>, std::vector<Eigen::Index>>;

/// Each pair's non-rigid residual: its grid point minus the similarity's image of its plan point.
Eigen::Matrix2Xd residuals(const ReferencePairs& pairs, const Eigen::Matrix3d& T) {
  Eigen::Matrix2Xd residual(2, pairs.size());
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    residual.col(i) =
        pairs.points_in_grid.col(i) -
        (T.topLeftCorner<2, 2>() * pairs.points_in_plan.col(i) + T.topRightCorner<2, 1>());
  return residual;
}

/// Which scan each pair came from.
std::vector<std::size_t> scan_of_pairs(const std::vector<std::size_t>& pairs_per_scan,
                                       std::size_t pairs) {
  std::vector<std::size_t> scan_of(pairs);
  std::size_t k = 0;
  for (std::size_t s = 0; s < pairs_per_scan.size(); ++s)
    for (std::size_t j = 0; j < pairs_per_scan[s] && k < scan_of.size(); ++j)
      scan_of[k++] = s;
  return scan_of;
}

/// The pairs of each plan cell of `cell` metres.
Cells cells_of(const ReferencePairs& pairs, double cell) {
  Cells cells;
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector2d p = pairs.points_in_plan.col(i) / cell;
    cells[{static_cast<long>(std::floor(p.x())), static_cast<long>(std::floor(p.y()))}].push_back(
        i);
  }
  return cells;
}

/// The upper median of `sorted` without the entries at `skip` (positions in it, ascending):
/// the (n - k) / 2-th of the rest, found by stepping over the skipped positions before it.
double upper_median_without(const std::vector<double>& sorted,
                            const std::vector<std::size_t>& skip) {
  std::size_t at = (sorted.size() - skip.size()) / 2;
  for (const std::size_t p : skip) {
    if (p > at)
      break;
    ++at;
  }
  return sorted[at];
}

/// Per scan: each of its pairs' deviation from the median residual of the other scans' pairs
/// in its cell (where those are enough for a consensus). A cell's residuals are sorted once and
/// each scan's consensus read off them past its own pairs: O(m log m) for a cell of m pairs,
/// where comparing every pair with every other was O(m^2), and a long run revisits every cell.
std::vector<std::vector<double>> deviations_per_scan(const Cells& cells,
                                                     const Eigen::Matrix2Xd& residual,
                                                     const std::vector<std::size_t>& scan_of,
                                                     std::size_t scans,
                                                     const OutlierScanOptions& options) {
  std::vector<std::vector<double>> deviations(scans);
  std::vector<std::size_t> order, rank_x, rank_y, by_scan, skip_x, skip_y;
  std::vector<double> sorted_x, sorted_y;
  const auto rank_along = [&](const std::vector<Eigen::Index>& members, int axis,
                              std::vector<double>& sorted, std::vector<std::size_t>& rank) {
    const std::size_t m = members.size();
    order.resize(m);
    for (std::size_t k = 0; k < m; ++k)
      order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return residual(axis, members[a]) < residual(axis, members[b]);
    });
    sorted.resize(m);
    rank.resize(m);
    for (std::size_t r = 0; r < m; ++r) {
      sorted[r] = residual(axis, members[order[r]]);
      rank[order[r]] = r;
    }
  };
  for (const auto& [cell, members] : cells) {
    const std::size_t m = members.size();
    rank_along(members, 0, sorted_x, rank_x);
    rank_along(members, 1, sorted_y, rank_y);
    // The cell's pairs by scan, each scan's pairs together.
    by_scan.resize(m);
    for (std::size_t k = 0; k < m; ++k)
      by_scan[k] = k;
    std::stable_sort(by_scan.begin(), by_scan.end(), [&](std::size_t a, std::size_t b) {
      return scan_of[static_cast<std::size_t>(members[a])] <
             scan_of[static_cast<std::size_t>(members[b])];
    });
    for (std::size_t first = 0; first < m;) {
      const std::size_t scan = scan_of[static_cast<std::size_t>(members[by_scan[first]])];
      std::size_t last = first;
      while (last < m && scan_of[static_cast<std::size_t>(members[by_scan[last]])] == scan)
        ++last;
      const std::size_t own = last - first;
      if (m - own >= options.min_cell_pairs) {
        skip_x.clear();
        skip_y.clear();
        for (std::size_t k = first; k < last; ++k) {
          skip_x.push_back(rank_x[by_scan[k]]);
          skip_y.push_back(rank_y[by_scan[k]]);
        }
        std::sort(skip_x.begin(), skip_x.end());
        std::sort(skip_y.begin(), skip_y.end());
        const Eigen::Vector2d consensus(upper_median_without(sorted_x, skip_x),
                                        upper_median_without(sorted_y, skip_y));
        for (std::size_t k = first; k < last; ++k)
          deviations[scan].push_back((residual.col(members[by_scan[k]]) - consensus).norm());
      }
      first = last;
    }
  }
  return deviations;
}

/// Per scan: whether its pairs lie grossly off the similarity (their median residual beyond
/// the gross limit), unless so many pairs are that the map itself is distorted.
std::vector<std::uint8_t> gross_scans(const Eigen::Matrix2Xd& residual,
                                      const std::vector<std::size_t>& scan_of, std::size_t scans,
                                      const OutlierScanOptions& options) {
  std::vector<double> norms(static_cast<std::size_t>(residual.cols()));
  for (Eigen::Index i = 0; i < residual.cols(); ++i)
    norms[static_cast<std::size_t>(i)] = residual.col(i).norm();
  const double limit =
      std::max(options.max_gross_residual, options.gross_residual_scales * upper_median(norms));
  std::vector<std::uint8_t> gross(scans, 0);
  const auto beyond =
      std::count_if(norms.begin(), norms.end(), [&](double r) { return r > limit; });
  if (static_cast<double>(beyond) > options.max_gross_fraction * static_cast<double>(norms.size()))
    return gross;
  std::vector<std::vector<double>> per_scan(scans);
  for (std::size_t i = 0; i < norms.size(); ++i)
    per_scan[scan_of[i]].push_back(norms[i]);
  for (std::size_t s = 0; s < scans; ++s)
    gross[s] = !per_scan[s].empty() && upper_median(per_scan[s]) > limit;
  return gross;
}

}  // namespace

std::size_t reject_outlier_scans(ReferencePairs& pairs, std::vector<std::size_t>& pairs_per_scan,
                                 const OutlierScanOptions& options) {
  if (!options.enabled || static_cast<std::size_t>(pairs.size()) < options.min_pairs)
    return 0;
  RansacOptions ransac;
  ransac.inlier_threshold = options.similarity_inlier_threshold;
  const RansacResult global = ransac_transform(pairs, ransac);
  if (!global.ok)
    return 0;
  const Eigen::Index n = pairs.size();
  const std::vector<std::size_t> scan_of =
      scan_of_pairs(pairs_per_scan, static_cast<std::size_t>(n));
  const Eigen::Matrix2Xd residual = residuals(pairs, global.estimate.T_grid_plan);
  std::vector<std::vector<double>> deviations = deviations_per_scan(
      cells_of(pairs, options.cell), residual, scan_of, pairs_per_scan.size(), options);
  // Drop the scans grossly off, and those whose median deviation is too large.
  std::vector<std::uint8_t> drop = gross_scans(residual, scan_of, pairs_per_scan.size(), options);
  for (std::size_t s = 0; s < deviations.size(); ++s) {
    if (deviations[s].size() >= options.min_scan_pairs &&
        upper_median(deviations[s]) > options.max_deviation)
      drop[s] = 1;
  }
  PairCollector kept;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (drop[scan_of[static_cast<std::size_t>(i)]])
      continue;
    kept.plan.push_back(pairs.points_in_plan.col(i));
    kept.grid.push_back(pairs.points_in_grid.col(i));
  }
  std::size_t dropped = 0;
  for (std::size_t s = 0; s < pairs_per_scan.size(); ++s) {
    if (drop[s]) {
      pairs_per_scan[s] = 0;
      ++dropped;
    }
  }
  pairs = kept.pairs();
  return dropped;
}

}  // namespace floorgrid
