#include "floorgrid/mapping/pair_noise.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

bool for_each_visit_difference(const ReferencePairs& pairs, const PairNoiseOptions& options,
                               const VisitDifference& visit) {
  const Eigen::Index n = pairs.size();
  if (n < 3 || options.stretches < 2 || options.queries == 0)
    return false;
  // The linear part of the pairs' similarity: neighbours' plan offsets carried into the grid.
  TransformEstimationOptions similarity;
  similarity.kind = TransformKind::similarity;
  Eigen::Matrix2d linear;
  try {
    linear = estimate_transform(pairs.points_in_plan, pairs.points_in_grid, similarity)
                 .T_grid_plan.topLeftCorner<2, 2>();
  } catch (const InputError&) {
    return false;  // degenerate pairs (one place): nothing to compare
  }
  // The place's radius in the plan's units: options.radius is grid (world) metres.
  const double scale =
      std::sqrt(std::abs(linear(0, 0) * linear(1, 1) - linear(0, 1) * linear(1, 0)));
  if (!(scale > 0.0) || !std::isfinite(scale))
    return false;
  const double radius = options.radius / scale;
  const auto stretch_of = [&](Eigen::Index i) {
    return run_stretch(static_cast<std::size_t>(i), static_cast<std::size_t>(n), options.stretches);
  };
  const PointIndex2D index(pairs.points_in_plan);
  const std::size_t queries = std::min(options.queries, static_cast<std::size_t>(n));
  for (std::size_t q = 0; q < queries; ++q) {
    const auto i = static_cast<Eigen::Index>(q * static_cast<std::size_t>(n) / queries);
    std::size_t used = 0;
    for (const PointIndex2D::Neighbour& m : index.within(pairs.points_in_plan.col(i), radius)) {
      if (used == options.neighbours)
        break;
      if (stretch_of(m.index) == stretch_of(i))
        continue;
      visit(i, (pairs.points_in_grid.col(m.index) - pairs.points_in_grid.col(i)) -
                   linear * (pairs.points_in_plan.col(m.index) - pairs.points_in_plan.col(i)));
      ++used;
    }
  }
  return true;
}

std::optional<PairNoise> pair_noise(const ReferencePairs& pairs, const PairNoiseOptions& options) {
  PairNoise noise;
  double sum = 0.0;
  const bool formed =
      for_each_visit_difference(pairs, options, [&](Eigen::Index, const Eigen::Vector2d& d) {
        sum += 0.5 * d.squaredNorm();
        ++noise.differences;
      });
  if (!formed || noise.differences < std::max<std::size_t>(options.min_differences, 1))
    return std::nullopt;
  noise.mean_square_m2 = sum / static_cast<double>(noise.differences);
  return noise;
}

std::optional<DirectionalPairNoise> pair_noise_along(const ReferencePairs& pairs,
                                                     const std::vector<Eigen::Vector2d>& along,
                                                     const PairNoiseOptions& options) {
  if (along.size() != static_cast<std::size_t>(pairs.size()))
    return std::nullopt;
  DirectionalPairNoise noise;
  double sum_along = 0.0, sum_across = 0.0;
  const bool formed =
      for_each_visit_difference(pairs, options, [&](Eigen::Index i, const Eigen::Vector2d& d) {
        const Eigen::Vector2d& t = along[static_cast<std::size_t>(i)];
        if (!(t.squaredNorm() > 0.0))
          return;
        // Each axis holds the two visits' errors: half its mean square is one pair's.
        sum_along += 0.5 * std::pow(d.dot(t), 2);
        sum_across += 0.5 * std::pow(d.x() * t.y() - d.y() * t.x(), 2);
        ++noise.differences;
      });
  if (!formed || noise.differences < std::max<std::size_t>(options.min_differences, 1))
    return std::nullopt;
  noise.along_m2 = sum_along / static_cast<double>(noise.differences);
  noise.across_m2 = sum_across / static_cast<double>(noise.differences);
  return noise;
}

}  // namespace floorgrid
