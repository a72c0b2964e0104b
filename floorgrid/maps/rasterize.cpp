#include "floorgrid/maps/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

double distance_to_segment(const Eigen::Vector2d& point, const Segment& segment) {
  const Eigen::Vector2d d = segment.b - segment.a;
  const double length_sq = d.squaredNorm();
  if (length_sq == 0.0)
    return (point - segment.a).norm();
  const double t = std::clamp((point - segment.a).dot(d) / length_sq, 0.0, 1.0);
  return (point - (segment.a + t * d)).norm();
}

double distance_to_arc(const Eigen::Vector2d& point, const Arc& arc) {
  const Eigen::Vector2d r = point - arc.center;
  if (arc.sweeps(std::atan2(r.y(), r.x())))
    return std::abs(r.norm() - arc.radius);
  return std::min((point - arc.point_at(arc.start_angle)).norm(),
                  (point - arc.point_at(arc.end_angle)).norm());
}

namespace {

/// Marks every cell whose centre is within `reach` of the primitive, visiting only the cells of
/// the primitive's bounding box grown by `reach`.
template <typename Distance>
void mark_within(OccupancyGrid& grid, const Eigen::AlignedBox2d& box, double reach,
                 const Distance& distance) {
  const GridGeometry& g = grid.geometry();
  Eigen::AlignedBox2d cells;
  const Eigen::Vector2d lo = box.min().array() - reach;
  const Eigen::Vector2d hi = box.max().array() + reach;
  for (const auto& corner :
       {lo, hi, Eigen::Vector2d(lo.x(), hi.y()), Eigen::Vector2d(hi.x(), lo.y())}) {
    cells.extend(g.to_cell_coordinates(corner));
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(cells.min().x())));
  const int y0 = std::max(0, static_cast<int>(std::floor(cells.min().y())));
  const int x1 = std::min(g.width - 1, static_cast<int>(std::floor(cells.max().x())));
  const int y1 = std::min(g.height - 1, static_cast<int>(std::floor(cells.max().y())));
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) {
      if (grid.state(ix, iy) == CellState::occupied)
        continue;
      if (distance(g.cell_center(ix, iy)) <= reach)
        grid.set_state(ix, iy, CellState::occupied);
    }
  }
}

/// Marks the cells within `reach` of a segment. Works row by row in cell coordinates so that a
/// long diagonal wall costs its length times its thickness, not its bounding box.
void mark_segment(OccupancyGrid& grid, const Segment& segment, double reach) {
  const GridGeometry& g = grid.geometry();
  const Eigen::Vector2d a = g.to_cell_coordinates(segment.a);
  const Eigen::Vector2d b = g.to_cell_coordinates(segment.b);
  const double r = reach / g.resolution;
  const Segment in_cells{a, b, 0};
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - r)));
  const int y1 = std::min(g.height - 1, static_cast<int>(std::floor(std::max(a.y(), b.y()) + r)));
  for (int iy = y0; iy <= y1; ++iy) {
    const double yc = iy + 0.5;
    // The part of the segment within the band |y - yc| <= r, grown by r, bounds the row's cells.
    double t0 = 0.0, t1 = 1.0;
    const double dy = b.y() - a.y();
    if (dy != 0.0) {
      double ta = (yc - r - a.y()) / dy, tb = (yc + r - a.y()) / dy;
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1)
        continue;
    } else if (std::abs(a.y() - yc) > r) {
      continue;
    }
    const double xa = a.x() + t0 * (b.x() - a.x()), xb = a.x() + t1 * (b.x() - a.x());
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min(xa, xb) - r)));
    const int x1 = std::min(g.width - 1, static_cast<int>(std::floor(std::max(xa, xb) + r)));
    for (int ix = x0; ix <= x1; ++ix) {
      if (distance_to_segment({ix + 0.5, yc}, in_cells) <= r) {
        grid.set_state(ix, iy, CellState::occupied);
      }
    }
  }
}

}  // namespace

OccupancyGrid rasterize(const VectorFloorplan& plan, const RasterizeOptions& options,
                        const std::optional<GridGeometry>& geometry) {
  if (!(options.resolution > 0.0)) {
    throw InputError("must be > 0 (got " + std::to_string(options.resolution) + ")", {}, 0,
                     "rasterize.resolution");
  }
  if (!(options.wall_thickness >= 0.0)) {
    throw InputError("must be >= 0 (got " + std::to_string(options.wall_thickness) + ")", {}, 0,
                     "rasterize.wall_thickness");
  }
  if (plan.empty())
    throw InputError("the floorplan holds no wall geometry to rasterize");

  GridGeometry g;
  if (geometry) {
    g = *geometry;
  } else {
    const Eigen::AlignedBox2d box = plan.bounds();
    const double cells_x = std::ceil((box.sizes().x() + 2.0 * options.margin) / options.resolution);
    const double cells_y = std::ceil((box.sizes().y() + 2.0 * options.margin) / options.resolution);
    if (cells_x * cells_y > static_cast<double>(options.max_cells)) {
      std::ostringstream message;
      message << "the plan spans " << box.sizes().x() << " x " << box.sizes().y() << " m: at "
              << options.resolution << " m per cell its grid would have more than "
              << options.max_cells << " cells (are its units right?)";
      throw InputError(message.str(), {}, 0, "rasterize.resolution");
    }
    g.width = std::max(1, static_cast<int>(cells_x));
    g.height = std::max(1, static_cast<int>(cells_y));
    g.resolution = options.resolution;
    g.origin = {box.min().x() - options.margin, box.min().y() - options.margin, 0.0};
  }

  OccupancyGrid grid(g, CellState::free);
  const double reach = 0.5 * std::max(options.wall_thickness, g.resolution);
  for (const Segment& s : plan.segments())
    mark_segment(grid, s, reach);
  for (const Arc& arc : plan.arcs()) {
    const Eigen::AlignedBox2d box(arc.center.array() - arc.radius, arc.center.array() + arc.radius);
    mark_within(grid, box, reach,
                [&](const Eigen::Vector2d& p) { return distance_to_arc(p, arc); });
  }
  return grid;
}

}  // namespace floorgrid
