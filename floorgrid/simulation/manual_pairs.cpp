#include "floorgrid/simulation/manual_pairs.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

namespace {
bool occupied_near(const OccupancyGrid& grid, const Eigen::Vector2d& point, int reach) {
  const Eigen::Vector2d c = grid.geometry().to_cell_coordinates(point);
  const int ix = static_cast<int>(std::floor(c.x())), iy = static_cast<int>(std::floor(c.y()));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (grid.is_occupied(ix + dx, iy + dy))
        return true;
    }
  }
  return false;
}
}  // namespace

ReferencePairs emulate_manual_pairs(const std::vector<Eigen::Vector2d>& corners_in_world,
                                    const PlanTruth& truth, double plan_scale,
                                    const OccupancyGrid& gridmap, const ManualPairsOptions& options,
                                    Random& random) {
  std::vector<Eigen::Vector2d> visible;
  for (const auto& corner : corners_in_world) {
    if (occupied_near(gridmap, truth.warp().world_to_grid(corner), options.visible_within)) {
      visible.push_back(corner);
    }
  }
  // A partial Fisher-Yates shuffle picks the corners.
  const int wanted = static_cast<int>(random.integer(options.min_pairs, options.max_pairs));
  const std::size_t n = std::min(visible.size(), static_cast<std::size_t>(wanted));
  for (std::size_t i = 0; i < n; ++i) {
    const auto j = static_cast<std::size_t>(random.integer(
        static_cast<std::int64_t>(i), static_cast<std::int64_t>(visible.size()) - 1));
    std::swap(visible[i], visible[j]);
  }
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, static_cast<Eigen::Index>(n));
  pairs.points_in_grid.resize(2, static_cast<Eigen::Index>(n));
  const double sigma = options.noise / std::sqrt(2.0);  // per axis, for the radial sigma
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    pairs.points_in_plan.col(k) = visible[i] * plan_scale;
    pairs.points_in_grid.col(k) = truth.warp().world_to_grid(visible[i]) +
                                  Eigen::Vector2d(random.normal(sigma), random.normal(sigma));
  }
  return pairs;
}

}  // namespace floorgrid
