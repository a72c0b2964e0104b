#include "floorgrid/simulation/segment_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "floorgrid/core/error.hpp"

namespace floorgrid {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Narrows [t0, t1] to where the ray is inside the slab lo <= o + t d <= hi.
bool clip_to_slab(double o, double d, double lo, double hi, double& t0, double& t1) {
  if (d == 0.0)
    return o >= lo && o <= hi;
  double ta = (lo - o) / d;
  double tb = (hi - o) / d;
  if (ta > tb)
    std::swap(ta, tb);
  t0 = std::max(t0, ta);
  t1 = std::min(t1, tb);
  return t0 <= t1;
}

int clamp_cell(double cell_coordinate, int cells) {
  if (!(cell_coordinate >= 0.0))
    return 0;
  if (cell_coordinate >= cells)
    return cells - 1;
  return static_cast<int>(cell_coordinate);
}

bool finite(const Eigen::Vector2d& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}

}  // namespace

std::optional<double> intersect_ray_segment(const Eigen::Vector2d& origin,
                                            const Eigen::Vector2d& direction,
                                            const Segment& segment, double max_range) {
  const Eigen::Vector2d e = segment.b - segment.a;
  const double t = detail::ray_segment_range(origin.x(), origin.y(), direction.x(), direction.y(),
                                             segment.a.x(), segment.a.y(), e.x(), e.y());
  if (t <= max_range)
    return t;
  return std::nullopt;
}

SegmentRayCaster::SegmentRayCaster(std::vector<Segment> segments_in_world,
                                   const SegmentRayCasterOptions& options)
    : segments_(std::move(segments_in_world)) {
  if (!(std::isfinite(options.cell_size) && options.cell_size > 0.0))
    throw InputError("must be a finite number > 0 (got " + std::to_string(options.cell_size) + ")",
                     {}, 0, "ray_caster.cell_size");
  if (segments_.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("too many segments (" + std::to_string(segments_.size()) + ")", {}, 0,
                     "segments");
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    if (!finite(segments_[i].a) || !finite(segments_[i].b))
      throw InputError("segment " + std::to_string(i) + " has a coordinate that is not finite", {},
                       0, "segments");
  }
  build_grid(options.cell_size, std::max<std::size_t>(options.max_cells, 1));
}

// Calls visit(ix, iy) for every cell that comes within pad_ of the segment: per column of cells
// (widened by the pad), the part of the segment over it gives a y range, widened by the pad.
template <typename Visit>
void SegmentRayCaster::for_each_cell_touched(const Segment& segment, Visit&& visit) const {
  const double ax = segment.a.x(), ay = segment.a.y();
  const double ex = segment.b.x() - ax, ey = segment.b.y() - ay;
  const double x_lo = std::min(ax, segment.b.x()) - pad_;
  const double x_hi = std::max(ax, segment.b.x()) + pad_;
  const int c0 = clamp_cell((x_lo - x0_) * inv_cell_size_, nx_);
  const int c1 = clamp_cell((x_hi - x0_) * inv_cell_size_, nx_);
  for (int c = c0; c <= c1; ++c) {
    double u0 = 0.0, u1 = 1.0;
    if (ex != 0.0) {
      const double column_lo = x0_ + c * cell_size_ - pad_;
      const double column_hi = x0_ + (c + 1) * cell_size_ + pad_;
      double ua = (column_lo - ax) / ex;
      double ub = (column_hi - ax) / ex;
      if (ua > ub)
        std::swap(ua, ub);
      u0 = std::clamp(ua, 0.0, 1.0);
      u1 = std::clamp(ub, 0.0, 1.0);
    }
    const double ya = ay + u0 * ey;
    const double yb = ay + u1 * ey;
    const int r0 = clamp_cell((std::min(ya, yb) - pad_ - y0_) * inv_cell_size_, ny_);
    const int r1 = clamp_cell((std::max(ya, yb) + pad_ - y0_) * inv_cell_size_, ny_);
    for (int r = r0; r <= r1; ++r)
      visit(c, r);
  }
}

void SegmentRayCaster::build_grid(double requested_cell_size, std::size_t max_cells) {
  if (segments_.empty()) {
    cell_size_ = requested_cell_size;
    inv_cell_size_ = 1.0 / cell_size_;
    nx_ = ny_ = 0;
    cell_begin_.assign(1, 0);
    return;
  }
  double x_min = kInf, y_min = kInf, x_max = -kInf, y_max = -kInf;
  for (const Segment& s : segments_) {
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      x_min = std::min(x_min, p.x());
      y_min = std::min(y_min, p.y());
      x_max = std::max(x_max, p.x());
      y_max = std::max(y_max, p.y());
    }
  }
  // The pad covers rounding in the traversal (cell of the entry point, far boundaries) and the
  // endpoint tolerance; it only ever adds registrations, never drops a hit.
  const double scale = std::max({1.0, std::abs(x_min), std::abs(x_max), std::abs(y_min),
                                 std::abs(y_max), x_max - x_min, y_max - y_min});
  pad_ = 1e-7 * scale;

  cell_size_ = requested_cell_size;
  for (;;) {
    x0_ = std::floor((x_min - pad_) / cell_size_) * cell_size_;
    y0_ = std::floor((y_min - pad_) / cell_size_) * cell_size_;
    const double nx = std::floor((x_max + pad_ - x0_) / cell_size_) + 1.0;
    const double ny = std::floor((y_max + pad_ - y0_) / cell_size_) + 1.0;
    if (nx * ny <= static_cast<double>(max_cells)) {
      nx_ = static_cast<int>(nx);
      ny_ = static_cast<int>(ny);
      break;
    }
    cell_size_ *= 2.0;
  }
  inv_cell_size_ = 1.0 / cell_size_;
  x1_ = x0_ + nx_ * cell_size_;
  y1_ = y0_ + ny_ * cell_size_;

  // Two passes (count, then fill) give each cell's entries contiguously, in segment order.
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<std::size_t> counts(cells + 1, 0);
  for (const Segment& s : segments_)
    for_each_cell_touched(s,
                          [&](int c, int r) { ++counts[static_cast<std::size_t>(r) * nx_ + c]; });
  std::size_t total = 0;
  for (std::size_t& n : counts) {
    const std::size_t here = n;
    n = total;
    total += here;
  }
  if (total >= std::numeric_limits<std::uint32_t>::max())
    throw InputError(
        "too many segment registrations (" + std::to_string(total) + "); use a larger cell size",
        {}, 0, "ray_caster.cell_size");
  cell_begin_.assign(counts.begin(), counts.end());
  entries_.resize(total);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    const CellEntry entry{s.a.x(), s.a.y(), s.b.x() - s.a.x(), s.b.y() - s.a.y(),
                          static_cast<std::uint32_t>(i)};
    for_each_cell_touched(s, [&](int c, int r) {
      entries_[counts[static_cast<std::size_t>(r) * nx_ + c]++] = entry;
    });
  }
}

std::optional<RayHit> SegmentRayCaster::cast(const Eigen::Vector2d& origin, double angle,
                                             double max_range) const {
  return cast_along(origin, Eigen::Vector2d(std::cos(angle), std::sin(angle)), max_range);
}

std::optional<RayHit> SegmentRayCaster::cast_along(const Eigen::Vector2d& origin,
                                                   const Eigen::Vector2d& direction,
                                                   double max_range) const {
  const double ox = origin.x(), oy = origin.y();
  const double dx = direction.x(), dy = direction.y();
  if (segments_.empty() || !finite(origin) || !finite(direction) || (dx == 0.0 && dy == 0.0) ||
      !(max_range > 0.0))
    return std::nullopt;

  double t_begin = 0.0, t_end = max_range;
  if (!clip_to_slab(ox, dx, x0_, x1_, t_begin, t_end) ||
      !clip_to_slab(oy, dy, y0_, y1_, t_begin, t_end))
    return std::nullopt;

  // Amanatides-Woo: the cell holding the entry point, then one neighbour at a time.
  int ix = clamp_cell((ox + t_begin * dx - x0_) * inv_cell_size_, nx_);
  int iy = clamp_cell((oy + t_begin * dy - y0_) * inv_cell_size_, ny_);
  const int step_x = dx > 0.0 ? 1 : (dx < 0.0 ? -1 : 0);
  const int step_y = dy > 0.0 ? 1 : (dy < 0.0 ? -1 : 0);
  const double inv_dx = 1.0 / dx, inv_dy = 1.0 / dy;
  // Far boundaries from the boundary coordinates themselves, so no error accumulates.
  auto x_boundary = [&](int c) {
    return step_x == 0 ? kInf : (x0_ + (c + (step_x > 0 ? 1 : 0)) * cell_size_ - ox) * inv_dx;
  };
  auto y_boundary = [&](int r) {
    return step_y == 0 ? kInf : (y0_ + (r + (step_y > 0 ? 1 : 0)) * cell_size_ - oy) * inv_dy;
  };
  double t_next_x = x_boundary(ix);
  double t_next_y = y_boundary(iy);

  double best = kInf;
  std::uint32_t best_index = 0;
  for (;;) {
    const std::size_t cell = static_cast<std::size_t>(iy) * nx_ + ix;
    const CellEntry* entry = entries_.data() + cell_begin_[cell];
    const CellEntry* const end = entries_.data() + cell_begin_[cell + 1];
    for (; entry != end; ++entry) {
      const double t =
          detail::ray_segment_range(ox, oy, dx, dy, entry->ax, entry->ay, entry->ex, entry->ey);
      if (t < best || (t == best && entry->index < best_index)) {
        best = t;
        best_index = entry->index;
      }
    }
    const double t_far = std::min(t_next_x, t_next_y);
    // Every hit nearer than t_far lies in a cell already walked, so it has been tested.
    if (best <= t_far - pad_ || t_far >= t_end)
      break;
    if (t_next_x < t_next_y) {
      ix += step_x;
      if (ix < 0 || ix >= nx_)
        break;
      t_next_x = x_boundary(ix);
    } else {
      iy += step_y;
      if (iy < 0 || iy >= ny_)
        break;
      t_next_y = y_boundary(iy);
    }
  }
  if (!(best <= max_range))
    return std::nullopt;
  return RayHit{best, best_index, segments_[best_index].layer};
}

}  // namespace floorgrid
