#include "floorgrid/pipeline/wall_faces.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>

#include "floorgrid/maps/wall_surface_field.hpp"

namespace floorgrid {

namespace {

bool is_wall(CellState s) {
  return s == CellState::occupied;
}

}  // namespace

ExteriorWalls::ExteriorWalls(const OccupancyGrid& plan, double seal_radius)
    : plan_(plan), outside_(static_cast<std::size_t>(plan.width()) * plan.height(), 0) {
  const GridGeometry& g = plan.geometry();
  const double res = g.resolution;
  const auto index = [&](int ix, int iy) {
    return static_cast<std::size_t>(iy) * plan.width() + static_cast<std::size_t>(ix);
  };
  // Closing the gaps: only cells farther than the seal radius from every wall are flooded, so
  // an opening narrower than twice it lets no flood through.
  const DistanceField to_walls(plan, is_wall, seal_radius + 2.0 * res);
  // Then grown back up to the walls by the radius it was kept away from them, around the walls
  // only (a flood, never through a stroke).
  const int grow = static_cast<int>(std::ceil(seal_radius / res)) + 2;
  std::vector<int> steps(outside_.size(), -1);  // -1: not reached; else cells from the sealed
  std::deque<std::pair<int, int>> queue;
  // A sealed cell is entered only from a sealed one (or the raster's edge): the rooms' own
  // sealed cores stay out of reach through a doorway.
  const auto reach = [&](int ix, int iy, int step) {
    const std::size_t i = index(ix, iy);
    if (steps[i] >= 0 || is_wall(plan.state(ix, iy)))
      return;
    const bool sealed = to_walls.at(ix, iy) > seal_radius;
    if ((sealed && step > 1) || (!sealed && step > grow))
      return;
    steps[i] = sealed ? 0 : step;
    outside_[i] = 1;
    if (sealed)
      queue.emplace_front(ix, iy);
    else
      queue.emplace_back(ix, iy);
  };
  for (int ix = 0; ix < plan.width(); ++ix) {
    reach(ix, 0, 1);
    reach(ix, plan.height() - 1, 1);
  }
  for (int iy = 0; iy < plan.height(); ++iy) {
    reach(0, iy, 1);
    reach(plan.width() - 1, iy, 1);
  }
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop_front();
    const int step = steps[index(x, y)];
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      if (g.contains(x + dx, y + dy))
        reach(x + dx, y + dy, step + 1);
    }
  }
}

bool ExteriorWalls::exterior(const Eigen::Vector2d& surface, const Eigen::Vector2d& normal,
                             double max_depth) const {
  const double step = 0.5 * plan_.geometry().resolution;
  bool in_wall = false;
  for (double depth = step; depth <= max_depth; depth += step) {
    int ix = 0, iy = 0;
    if (!plan_.geometry().cell_of(surface - depth * normal, ix, iy))
      return false;
    if (is_wall(plan_.state(ix, iy))) {
      in_wall = true;
    } else if (in_wall) {
      return outside_[static_cast<std::size_t>(iy) * plan_.width() +
                      static_cast<std::size_t>(ix)] != 0;
    } else if (depth > 3.0 * step) {
      return false;  // no wall behind the surface point
    }
  }
  return false;
}

OccupancyGrid plan_at_faces(const OccupancyGrid& plan, const ExteriorWalls& exterior,
                            const WallFaceFit& fit, double max_depth) {
  OccupancyGrid out = plan;
  const double reach = std::max(fit.exterior_offset, fit.partition_offset);
  if (!fit.fitted || !(reach > 0.0))
    return out;
  const double step = plan.geometry().resolution;
  const WallSurfaceField field(plan, reach + 2.0 * step, WallSurfaceField::Line::surface);
  for (int iy = 0; iy < plan.height(); ++iy) {
    for (int ix = 0; ix < plan.width(); ++ix) {
      if (is_wall(plan.state(ix, iy)) || exterior.outside(ix, iy))
        continue;
      const Eigen::Vector2d c = plan.geometry().cell_center(ix, iy);
      const double d = field.distance(c);
      if (!(d <= reach))
        continue;
      const Eigen::Vector2d gradient(field.distance(c + Eigen::Vector2d(step, 0)) -
                                         field.distance(c - Eigen::Vector2d(step, 0)),
                                     field.distance(c + Eigen::Vector2d(0, step)) -
                                         field.distance(c - Eigen::Vector2d(0, step)));
      if (gradient.norm() < 1e-9)
        continue;
      const Eigen::Vector2d n = gradient.normalized();
      const bool outer = exterior.exterior(c - d * n, n, max_depth);
      if (d <= (outer ? fit.exterior_offset : fit.partition_offset))
        out.set_cell(ix, iy, CellState::occupied, kOccupancyOccupied);
    }
  }
  return out;
}

WallFaceFit fit_wall_faces(const FaceMatcher& match, const MapSimilarity& start,
                           const WallFaceOptions& o) {
  WallFaceFit fit;
  fit.similarity = start;
  if (!o.enabled) {
    fit.note = "off";
    return fit;
  }
  // x = (a, b, tx, ty, exterior offset, partition offset): s R g + t = [a -b; b a] g + t.
  Eigen::Matrix<double, 6, 1> x;
  x << start.scale * std::cos(start.theta), start.scale * std::sin(start.theta),
      start.translation.x(), start.translation.y(), 0.0, 0.0;
  const auto similarity_of = [](const Eigen::Matrix<double, 6, 1>& v) {
    MapSimilarity s;
    s.scale = std::hypot(v(0), v(1));
    s.theta = std::atan2(v(1), v(0));
    s.translation = v.segment<2>(2);
    return s;
  };
  for (int round = 0; round < o.iterations; ++round) {
    const MapSimilarity current = similarity_of(x);
    const std::vector<FaceObservation> observed = match(current, o.radius * current.scale);
    fit.exterior_points = static_cast<std::size_t>(std::count_if(
        observed.begin(), observed.end(), [](const FaceObservation& f) { return f.exterior; }));
    fit.partition_points = observed.size() - fit.exterior_points;
    if (fit.exterior_points < o.min_points || fit.partition_points < o.min_points) {
      fit.note = fmt::format(
          "too few wall points matched ({} on outer walls, {} on others; {} each needed)",
          fit.exterior_points, fit.partition_points, o.min_points);
      fit.similarity = start;
      return fit;
    }
    Eigen::Matrix<double, 6, 6> normal_matrix = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    const double huber = o.huber * current.scale;
    for (const FaceObservation& f : observed) {
      const Eigen::Vector2d& n = f.normal;
      const Eigen::Vector2d& g = f.grid_point;
      Eigen::Matrix<double, 6, 1> row;
      row << n.dot(g), n.y() * g.x() - n.x() * g.y(), n.x(), n.y(), f.exterior ? -1.0 : 0.0,
          f.exterior ? 0.0 : -1.0;
      const double target = n.dot(f.surface);
      const double residual = row.dot(x) - target;
      const double w = std::min(1.0, huber / std::max(std::abs(residual), 1e-12));
      normal_matrix += w * row * row.transpose();
      rhs += w * target * row;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normal_matrix);
    if (solver.info() != Eigen::Success) {
      fit.note = "the faces' fit is degenerate";
      fit.similarity = start;
      return fit;
    }
    const Eigen::Matrix<double, 6, 1> next = solver.solve(rhs);
    if (!next.allFinite()) {
      fit.note = "the faces' fit is degenerate";
      fit.similarity = start;
      return fit;
    }
    x = next;
  }
  const MapSimilarity refined = similarity_of(x);
  const double exterior_m = x(4) / refined.scale;
  const double partition_m = x(5) / refined.scale;
  const double change = start.scale / refined.scale - 1.0;  // of the plan scale, 1 / scale
  fit.exterior_offset = x(4);
  fit.partition_offset = x(5);
  const bool alike = exterior_m - partition_m < o.min_offset_difference;
  if (alike || exterior_m < -o.max_offset / 4 || exterior_m > o.max_offset ||
      std::abs(partition_m) > o.max_offset / 2 || std::abs(change) > o.max_scale_change) {
    fit.note = fmt::format(
        "not used: outer faces {:.3f} m and partition faces {:.3f} m off their strokes{}, the "
        "scale {:+.2f}%",
        exterior_m, partition_m, alike ? " (alike)" : "", 100.0 * change);
    fit.similarity = start;
    return fit;
  }
  fit.fitted = true;
  fit.similarity = refined;
  fit.note = fmt::format(
      "outer walls' faces {:.3f} m off their strokes into the rooms, partitions' {:.3f} m "
      "({} and {} wall points): the scale {:+.2f}%",
      exterior_m, partition_m, fit.exterior_points, fit.partition_points, 100.0 * change);
  return fit;
}

}  // namespace floorgrid
