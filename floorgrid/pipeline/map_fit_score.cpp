#include "floorgrid/pipeline/map_fit_score.hpp"

#include <numbers>

namespace floorgrid {

namespace {

// The centres of a grid's occupied cells.
std::vector<Eigen::Vector2d> occupied_centres(const OccupancyGrid& grid) {
  std::vector<Eigen::Vector2d> all;
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      if (grid.state(ix, iy) == CellState::occupied)
        all.push_back(grid.geometry().cell_center(ix, iy));
    }
  }
  return all;
}

}  // namespace

Eigen::Vector2d MapSimilarity::apply(const Eigen::Vector2d& g) const {
  return scale * (rotation_2d(theta) * g) + translation;
}

Eigen::Vector2d MapSimilarity::inverse(const Eigen::Vector2d& p) const {
  return rotation_2d(-theta) * (p - translation) / scale;
}

Pose2 MapSimilarity::apply(const Pose2& pose) const {
  const Eigen::Vector2d p = apply(pose.translation());
  return {p.x(), p.y(), normalize_angle(pose.theta + theta)};
}

bool distinct(const MapSimilarity& a, const MapSimilarity& b, const Eigen::Vector2d& centre) {
  if (std::abs(std::log(a.scale / b.scale)) > 0.05)
    return true;
  if (std::abs(std::remainder(a.theta - b.theta, 2 * std::numbers::pi)) >
      10.0 * std::numbers::pi / 180.0)
    return true;
  return (a.apply(centre) - b.apply(centre)).norm() / a.scale > 2.0;
}

std::vector<Eigen::Vector2d> evenly_thinned(const std::vector<Eigen::Vector2d>& points,
                                            std::size_t max_points) {
  if (max_points == 0 || points.size() <= max_points)
    return points;
  std::vector<Eigen::Vector2d> kept;
  kept.reserve(max_points);
  const double stride = double(points.size()) / double(max_points);
  for (std::size_t i = 0; i < max_points; ++i)
    kept.push_back(points[static_cast<std::size_t>(double(i) * stride)]);
  return kept;
}

MapFitScorer::MapFitScorer(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                           PlanWalls plan_walls, std::size_t max_points,
                           double free_violation_distance)
    : gridmap_(gridmap),
      plan_(plan),
      grid_cells_(occupied_centres(gridmap)),
      plan_cells_(occupied_centres(plan)),
      plan_field_(plan, 5.0,
                  plan_walls == PlanWalls::raster_strokes ? WallSurfaceField::Line::surface
                                                          : WallSurfaceField::Line::centre),
      grid_field_(occupied_distance_field(gridmap, 2.0)),
      free_violation_distance_(free_violation_distance) {
  use_points(max_points);
  for (const Eigen::Vector2d& g : grid_points_)
    centre_ += g;
  if (!grid_points_.empty())
    centre_ /= double(grid_points_.size());
}

void MapFitScorer::use_points(std::size_t max_points) {
  grid_points_ = evenly_thinned(grid_cells_, max_points);
  plan_points_ = evenly_thinned(plan_cells_, max_points);
}

ScoredSimilarity MapFitScorer::score(const MapSimilarity& t, double sigma) const {
  const MapFit fit = score([&](const Eigen::Vector2d& g) { return t.apply(g); },
                           [&](const Eigen::Vector2d& p) { return t.inverse(p); }, t.scale, sigma);
  return {fit, t};
}

void MapFitScorer::count_free_space(const Eigen::Vector2d& g, std::size_t& observed,
                                    std::size_t& violations) const {
  int ix = 0, iy = 0;
  if (!gridmap_.geometry().cell_of(g, ix, iy) || gridmap_.state(ix, iy) == CellState::unknown)
    return;
  ++observed;
  if (gridmap_.state(ix, iy) == CellState::free &&
      grid_field_.at(ix, iy) > free_violation_distance_)
    ++violations;
}

}  // namespace floorgrid
