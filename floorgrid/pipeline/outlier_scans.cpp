#include "floorgrid/pipeline/outlier_scans.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "floorgrid/geometry/ransac.hpp"
#include "floorgrid/localization/pair_extraction.hpp"

namespace floorgrid {

std::size_t reject_outlier_scans(ReferencePairs& pairs, std::vector<std::size_t>& pairs_per_scan,
                                 const OutlierScanOptions& o) {
  if (!o.enabled || pairs.size() < 100)
    return 0;
  RansacOptions ransac;
  ransac.inlier_threshold = 0.5;
  const RansacResult global = ransac_transform(pairs, ransac);
  if (!global.ok)
    return 0;
  const Eigen::Matrix3d& T = global.estimate.T_grid_plan;
  const Eigen::Index n = pairs.size();
  Eigen::Matrix2Xd residual(2, n);
  for (Eigen::Index i = 0; i < n; ++i)
    residual.col(i) =
        pairs.points_in_grid.col(i) -
        (T.topLeftCorner<2, 2>() * pairs.points_in_plan.col(i) + T.topRightCorner<2, 1>());
  // Which scan each pair came from, and the pairs of each cell.
  std::vector<std::size_t> scan_of(static_cast<std::size_t>(n));
  {
    std::size_t k = 0;
    for (std::size_t s = 0; s < pairs_per_scan.size(); ++s)
      for (std::size_t j = 0; j < pairs_per_scan[s] && k < scan_of.size(); ++j)
        scan_of[k++] = s;
  }
  std::map<std::pair<long, long>, std::vector<Eigen::Index>> cells;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d p = pairs.points_in_plan.col(i) / o.cell;
    cells[{static_cast<long>(std::floor(p.x())), static_cast<long>(std::floor(p.y()))}].push_back(
        i);
  }
  // Each pair's deviation from the median residual of the other scans' pairs in its cell.
  std::vector<std::vector<double>> deviations(pairs_per_scan.size());
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
      if (xs.size() < o.min_cell_pairs)
        continue;
      const auto median = [](std::vector<double>& v) {
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        return v[v.size() / 2];
      };
      const Eigen::Vector2d consensus(median(xs), median(ys));
      deviations[scan_of[static_cast<std::size_t>(i)]].push_back(
          (residual.col(i) - consensus).norm());
    }
  }
  // Drop the scans whose median deviation is too large.
  std::vector<std::uint8_t> drop(pairs_per_scan.size(), 0);
  for (std::size_t s = 0; s < deviations.size(); ++s) {
    std::vector<double>& d = deviations[s];
    if (d.size() < 5)
      continue;
    std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
    drop[s] = d[d.size() / 2] > o.max_deviation;
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
