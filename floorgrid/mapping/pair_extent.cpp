#include "floorgrid/mapping/pair_extent.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

namespace {

/// The (k+1)-th smallest and (k+1)-th largest of `values` (O(n): selection).
std::pair<double, double> trimmed_range(std::vector<double> values, std::size_t k) {
  const auto lo = values.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(values.begin(), lo, values.end());
  const double low = *lo;
  const auto hi = values.end() - 1 - static_cast<std::ptrdiff_t>(k);
  std::nth_element(values.begin(), hi, values.end());
  return {low, *hi};
}

}  // namespace

Eigen::AlignedBox2d robust_box(const Eigen::Ref<const Eigen::Matrix2Xd>& points, double trim) {
  const auto n = static_cast<std::size_t>(points.cols());
  Eigen::AlignedBox2d box;
  if (n == 0)
    return box;
  std::size_t k = 0;
  if (n >= 5) {
    k = std::max<std::size_t>(1,
                              static_cast<std::size_t>(std::ceil(trim * static_cast<double>(n))));
    k = std::min(k, (n - 1) / 2);
  }
  Eigen::Vector2d lo, hi;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> values(n);
    for (std::size_t i = 0; i < n; ++i)
      values[i] = points(axis, static_cast<Eigen::Index>(i));
    std::tie(lo[axis], hi[axis]) = trimmed_range(std::move(values), k);
  }
  return {lo, hi};
}

double robust_extent(const Eigen::Ref<const Eigen::Matrix2Xd>& points, double trim) {
  const Eigen::AlignedBox2d box = robust_box(points, trim);
  return box.isEmpty() ? 0.0 : box.sizes().maxCoeff();
}

std::vector<FarPair> far_pairs(const ReferencePairs& pairs, const FarPairOptions& options) {
  std::vector<FarPair> far;
  if (static_cast<std::size_t>(pairs.size()) < std::max<std::size_t>(options.min_pairs, 1))
    return far;
  struct Side {
    const char* name;
    const Eigen::Matrix2Xd& points;
    Eigen::AlignedBox2d box;
    double extent;
  };
  std::vector<Side> sides;
  for (const auto& [name, points] :
       {std::pair<const char*, const Eigen::Matrix2Xd&>("plan", pairs.points_in_plan),
        {"grid", pairs.points_in_grid}}) {
    const Eigen::AlignedBox2d box = robust_box(points, options.trim);
    sides.push_back({name, points, box, box.sizes().maxCoeff()});
  }
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    for (const Side& side : sides) {
      if (!(side.extent > 0.0))
        continue;  // the bulk is one point: no scale to judge by
      const Eigen::Vector2d p = side.points.col(i);
      const double distance = side.box.exteriorDistance(p);
      if (distance > options.factor * side.extent) {
        const Eigen::Vector2d outside =
            (side.box.min() - p).cwiseMax(p - side.box.max()).cwiseMax(0.0);
        far.push_back({i, side.name, outside.y() > outside.x() ? 1 : 0, distance, side.extent});
        break;
      }
    }
  }
  return far;
}

}  // namespace floorgrid
