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

/// Per scan: each of its pairs' deviation from the median residual of the other scans' pairs
/// in its cell (where those are enough for a consensus).
std::vector<std::vector<double>> deviations_per_scan(const Cells& cells,
                                                     const Eigen::Matrix2Xd& residual,
                                                     const std::vector<std::size_t>& scan_of,
                                                     std::size_t scans,
                                                     const OutlierScanOptions& options) {
  std::vector<std::vector<double>> deviations(scans);
  std::vector<double> xs, ys;
  for (const auto& [cell, members] : cells) {
    for (const Eigen::Index i : members) {
      xs.clear();
      ys.clear();
      for (const Eigen::Index j : members) {
        if (scan_of[static_cast<std::size_t>(j)] == scan_of[static_cast<std::size_t>(i)])
          continue;
        xs.push_back(residual(0, j));
        ys.push_back(residual(1, j));
      }
      if (xs.size() < options.min_cell_pairs)
        continue;
      const Eigen::Vector2d consensus(upper_median(xs), upper_median(ys));
      deviations[scan_of[static_cast<std::size_t>(i)]].push_back(
          (residual.col(i) - consensus).norm());
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
