#include "floorgrid/mapping/pair_noise.hpp"

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

std::optional<PairNoise> pair_noise(const ReferencePairs& pairs, const PairNoiseOptions& options) {
  const Eigen::Index n = pairs.size();
  if (n < 3 || options.stretches < 2 || options.queries == 0)
    return std::nullopt;
  // The linear part of the pairs' similarity: neighbours' plan offsets carried into the grid.
  TransformEstimationOptions similarity;
  similarity.kind = TransformKind::similarity;
  Eigen::Matrix2d linear;
  try {
    linear = estimate_transform(pairs.points_in_plan, pairs.points_in_grid, similarity)
                 .T_grid_plan.topLeftCorner<2, 2>();
  } catch (const InputError&) {
    return std::nullopt;  // degenerate pairs (one place): nothing to compare
  }
  // The place's radius in the plan's units: options.radius is grid (world) metres.
  const double scale =
      std::sqrt(std::abs(linear(0, 0) * linear(1, 1) - linear(0, 1) * linear(1, 0)));
  if (!(scale > 0.0) || !std::isfinite(scale))
    return std::nullopt;
  const double radius = options.radius / scale;
  const auto stretch_of = [&](Eigen::Index i) {
    return run_stretch(static_cast<std::size_t>(i), static_cast<std::size_t>(n), options.stretches);
  };
  const PointIndex2D index(pairs.points_in_plan);
  const std::size_t queries = std::min(options.queries, static_cast<std::size_t>(n));
  PairNoise noise;
  double sum = 0.0;
  for (std::size_t q = 0; q < queries; ++q) {
    const auto i = static_cast<Eigen::Index>(q * static_cast<std::size_t>(n) / queries);
    std::size_t used = 0;
    for (const PointIndex2D::Neighbour& m : index.within(pairs.points_in_plan.col(i), radius)) {
      if (used == options.neighbours)
        break;
      if (stretch_of(m.index) == stretch_of(i))
        continue;
      const Eigen::Vector2d d =
          (pairs.points_in_grid.col(m.index) - pairs.points_in_grid.col(i)) -
          linear * (pairs.points_in_plan.col(m.index) - pairs.points_in_plan.col(i));
      sum += 0.5 * d.squaredNorm();
      ++used;
    }
    noise.differences += used;
  }
  if (noise.differences < std::max<std::size_t>(options.min_differences, 1))
    return std::nullopt;
  noise.mean_square_m2 = sum / static_cast<double>(noise.differences);
  return noise;
}

}  // namespace floorgrid
