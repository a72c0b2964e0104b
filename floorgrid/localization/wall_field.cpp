#include "floorgrid/localization/wall_field.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

void validate(const WallFieldOptions& o) {
  if (!(o.max_distance > 0.0) || !std::isfinite(o.max_distance))
    throw InputError("must be > 0", {}, 0, "wall_field.max_distance");
  if (o.normal_radius < 1)
    throw InputError("must be >= 1", {}, 0, "wall_field.normal_radius");
  if (!(o.max_flatness > 0.0 && o.max_flatness < 1.0))
    throw InputError("must be in (0, 1)", {}, 0, "wall_field.max_flatness");
}

Eigen::Vector2d occupied_line_normal(const OccupancyGrid& grid, const Eigen::Vector2d& centre,
                                     double radius, double max_flatness, int min_cells) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d outer = Eigen::Matrix2d::Zero();
  int n = 0;
  const int y0 = static_cast<int>(std::floor(centre.y() - radius));
  const int x0 = static_cast<int>(std::floor(centre.x() - radius));
  for (int iy = y0; iy <= static_cast<int>(std::floor(centre.y() + radius)); ++iy) {
    for (int ix = x0; ix <= static_cast<int>(std::floor(centre.x() + radius)); ++ix) {
      const Eigen::Vector2d d = Eigen::Vector2d(ix + 0.5, iy + 0.5) - centre;
      if (d.squaredNorm() > radius * radius || !grid.is_occupied(ix, iy))
        continue;
      sum += d;
      outer += d * d.transpose();
      ++n;
    }
  }
  if (n < std::max(min_cells, 1))
    return Eigen::Vector2d::Zero();
  const Eigen::Vector2d mean = sum / n;
  const Eigen::Matrix2d scatter = outer / n - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
  const double small = eigen.eigenvalues()(0), large = eigen.eigenvalues()(1);
  if (!(large > 0.0) || small > max_flatness * large)
    return Eigen::Vector2d::Zero();
  // Cell axes are the grid's axes; the grid's yaw turns them into the map frame.
  return (grid.geometry().origin.rotation() * eigen.eigenvectors().col(0)).normalized();
}

namespace {

/// The wall's normal at occupied cell (ix, iy), from the occupied cells around it.
Eigen::Vector2f wall_normal(const OccupancyGrid& grid, int ix, int iy,
                            const WallFieldOptions& options) {
  return occupied_line_normal(grid, {ix + 0.5, iy + 0.5}, options.normal_radius,
                              options.max_flatness, 3)
      .cast<float>();
}

/// Whether cell (ix, iy) or one of its eight neighbours is occupied.
bool near_occupied(const OccupancyGrid& grid, int ix, int iy) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (grid.is_occupied(ix + dx, iy + dy))
        return true;
  return false;
}

}  // namespace

WallField::WallField(const OccupancyGrid& grid, const WallFieldOptions& options,
                     const std::vector<std::uint8_t>* rooms)
    : geometry_(grid.geometry()) {
  validate(options);
  const int w = geometry_.width, h = geometry_.height;
  std::vector<std::int32_t> wall_of_cell(geometry_.size(), -1);
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      if (grid.state(ix, iy) != CellState::occupied)
        continue;
      wall_of_cell[static_cast<std::size_t>(iy) * w + ix] =
          static_cast<std::int32_t>(walls_.size());
      walls_.push_back(
          {geometry_.cell_center(ix, iy).cast<float>(), wall_normal(grid, ix, iy, options)});
    }
  }
  if (rooms)
    orient(*rooms);
  build_lookup(wall_of_cell, options.max_distance);
}

WallField::WallField(const VectorFloorplan& plan, const GridGeometry& geometry,
                     const WallFieldOptions& options, const OccupancyGrid* visible,
                     const std::vector<std::uint8_t>* rooms)
    : geometry_(geometry) {
  validate(options);
  std::vector<std::int32_t> wall_of_cell(geometry_.size(), -1);
  std::vector<double> distance_of_cell(geometry_.size(), 0.0);
  const double step = 0.25 * geometry_.resolution;
  const auto add_segment = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double length = ab.norm();
    const Eigen::Vector2d normal = length > 0.0
                                       ? Eigen::Vector2d(Eigen::Vector2d(-ab.y(), ab.x()) / length)
                                       : Eigen::Vector2d(Eigen::Vector2d::Zero());
    const int samples = static_cast<int>(std::ceil(length / step));
    for (int k = 0; k <= samples; ++k) {
      const Eigen::Vector2d p = samples ? a + ab * (static_cast<double>(k) / samples) : a;
      int ix = 0, iy = 0;
      if (!geometry_.cell_of(p, ix, iy))
        continue;
      if (visible && !near_occupied(*visible, ix, iy))
        continue;
      // The segment's point nearest the cell centre, and how near it is.
      const Eigen::Vector2d c = geometry_.cell_center(ix, iy);
      const double t =
          length > 0.0 ? std::clamp((c - a).dot(ab) / (length * length), 0.0, 1.0) : 0.0;
      const Eigen::Vector2d nearest = a + t * ab;
      const double distance = (nearest - c).norm();
      const std::size_t cell = static_cast<std::size_t>(iy) * geometry_.width + ix;
      std::int32_t& slot = wall_of_cell[cell];
      if (slot >= 0 && distance_of_cell[cell] <= distance)
        continue;
      const WallPoint wall{nearest.cast<float>(), normal.cast<float>()};
      if (slot < 0) {
        slot = static_cast<std::int32_t>(walls_.size());
        walls_.push_back(wall);
      } else {
        walls_[static_cast<std::size_t>(slot)] = wall;
      }
      distance_of_cell[cell] = distance;
    }
  };
  for (const Segment& s : plan.segments())
    add_segment(s.a, s.b);
  for (const Arc& arc : plan.arcs()) {
    // Chords deviating at most a tenth of a cell from the arc: sagitta r (1 - cos(h / 2)).
    const double sweep = arc.end_angle - arc.start_angle;
    const double tolerance = 0.1 * geometry_.resolution;
    const double max_angle =
        arc.radius > tolerance ? 2.0 * std::acos(1.0 - tolerance / arc.radius) : sweep;
    const int pieces = std::max(1, static_cast<int>(std::ceil(sweep / max_angle)));
    for (int k = 0; k < pieces; ++k) {
      add_segment(arc.point_at(arc.start_angle + sweep * k / pieces),
                  arc.point_at(arc.start_angle + sweep * (k + 1) / pieces));
    }
  }
  if (rooms)
    orient(*rooms);
  build_lookup(wall_of_cell, options.max_distance);
}

void WallField::orient(const std::vector<std::uint8_t>& rooms) {
  if (rooms.size() != geometry_.size())
    return;
  // Probe a few cells out on each side of the wall along its normal.
  const auto room_at = [&](const Eigen::Vector2d& p) {
    int ix = 0, iy = 0;
    return geometry_.cell_of(p, ix, iy) &&
           rooms[static_cast<std::size_t>(iy) * geometry_.width + ix];
  };
  for (WallPoint& w : walls_) {
    if (w.normal.squaredNorm() < 0.5)
      continue;
    bool plus = false, minus = false;
    for (const double k : {1.5, 2.5, 3.5}) {
      const Eigen::Vector2d step = w.normal.cast<double>() * (k * geometry_.resolution);
      plus = plus || room_at(w.point.cast<double>() + step);
      minus = minus || room_at(w.point.cast<double>() - step);
    }
    if (plus != minus) {
      w.one_sided = true;
      if (minus)
        w.normal = -w.normal;
    }
  }
}

double WallField::distance(const Eigen::Vector2d& point_in_map) const {
  const WallPoint* wall = nearest(point_in_map);
  if (!wall)
    return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d offset = point_in_map - wall->point.cast<double>();
  const Eigen::Vector2d n = wall->normal.cast<double>();
  const double d = n.squaredNorm() > 0.5 ? std::abs(n.dot(offset)) : offset.norm();
  return std::max(0.0, d - surface_offset_);
}

void WallField::set_surface_offset(double metres) {
  if (!(metres >= 0.0 && metres <= geometry_.resolution))
    throw InputError("must be in [0, one cell]", {}, 0, "wall_field.surface_offset");
  surface_offset_ = metres;
}

void WallField::build_lookup(const std::vector<std::int32_t>& wall_of_cell, double max_distance) {
  const int w = geometry_.width, h = geometry_.height;
  nearest_.assign(geometry_.size(), -1);
  if (walls_.empty() || w == 0 || h == 0)
    return;
  // Walls are the zero pixels of OpenCV's transform; with per-pixel labels it also tells,
  // for every cell, which zero pixel is nearest (a discrete Voronoi diagram). It runs on strips
  // of rows, each with a margin beyond the cap above and below: a cell's nearest wall within
  // the cap lies inside its strip's margin, and the transform's paths between the two stay in
  // their bounding box, so each strip's answer is the whole map's while its buffers (the
  // transform's own, about 20 bytes a cell) stay a strip's size, not a 250 m building's.
  const double max_cells = max_distance / geometry_.resolution;
  const int margin = static_cast<int>(std::min<double>(h, std::ceil(1.1 * max_cells) + 2.0));
  constexpr int kStripRows = 256;
  std::vector<std::int32_t> wall_of_label;
  for (int y0 = 0; y0 < h; y0 += kStripRows) {
    const int y1 = std::min(h, y0 + kStripRows);
    const int top = std::max(0, y0 - margin), bottom = std::min(h, y1 + margin);
    cv::Mat source(bottom - top, w, CV_8UC1);
    bool any_wall = false;
    for (int iy = top; iy < bottom; ++iy) {
      auto* row = source.ptr<std::uint8_t>(iy - top);
      for (int ix = 0; ix < w; ++ix) {
        const bool wall = wall_of_cell[static_cast<std::size_t>(iy) * w + ix] >= 0;
        row[ix] = wall ? 0 : 255;
        any_wall = any_wall || wall;
      }
    }
    if (!any_wall)
      continue;  // no wall near these rows
    cv::Mat distance, labels;
    cv::distanceTransform(source, distance, labels, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
    // Each wall pixel carries its own label: label -> wall index.
    wall_of_label.assign(static_cast<std::size_t>(source.rows) * w + 1, -1);
    for (int iy = top; iy < bottom; ++iy) {
      const auto* label = labels.ptr<std::int32_t>(iy - top);
      for (int ix = 0; ix < w; ++ix) {
        const std::int32_t k = wall_of_cell[static_cast<std::size_t>(iy) * w + ix];
        if (k >= 0 && label[ix] >= 0 && static_cast<std::size_t>(label[ix]) < wall_of_label.size())
          wall_of_label[static_cast<std::size_t>(label[ix])] = k;
      }
    }
    for (int iy = y0; iy < y1; ++iy) {
      const auto* label = labels.ptr<std::int32_t>(iy - top);
      const float* d = distance.ptr<float>(iy - top);
      for (int ix = 0; ix < w; ++ix) {
        if (d[ix] > max_cells || label[ix] < 0 ||
            static_cast<std::size_t>(label[ix]) >= wall_of_label.size())
          continue;
        nearest_[static_cast<std::size_t>(iy) * w + ix] =
            wall_of_label[static_cast<std::size_t>(label[ix])];
      }
    }
  }
}

}  // namespace floorgrid
