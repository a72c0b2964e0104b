#include "floorgrid/simulation/slam_map.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

/// The world ray a beam traces: from the laser, `length` metres along `direction`.
struct BeamRay {
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  double length = 0.0;     // metres
  bool is_return = false;  // ends in a hit
};

std::optional<BeamRay> beam_ray(const SlamMapInput& scan, std::size_t i,
                                const SlamMapOptions& options) {
  const double reading = scan.ranges[i];
  if (!std::isfinite(reading) && reading != std::numeric_limits<double>::infinity())
    return std::nullopt;  // NaN or -inf
  if (!(reading > 0.0))
    return std::nullopt;
  const double angle = scan.laser_pose_in_world.theta +
                       (scan.start_angle + static_cast<double>(i) * scan.angle_increment);
  BeamRay ray;
  ray.direction = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  ray.is_return = reading < scan.max_range;
  ray.length = ray.is_return ? reading : options.free_range_for_no_return.value_or(scan.max_range);
  if (!(std::isfinite(ray.length) && ray.length > 0.0))
    return std::nullopt;  // a no-return of a scan whose max_range is unusable
  return ray;
}

int piece_count(double length, double max_piece_length) {
  return std::max(1, static_cast<int>(std::ceil(length / max_piece_length)));
}

// The world point at the end of piece k of n; the last is the beam's end exactly.
Eigen::Vector2d piece_end(const Eigen::Vector2d& origin, const BeamRay& ray, int k, int n) {
  const double s = k == n ? ray.length : ray.length * k / n;
  return origin + s * ray.direction;
}

Eigen::Vector2d checked_warp(const WorldToGrid& world_to_grid, const Eigen::Vector2d& p) {
  const Eigen::Vector2d g = world_to_grid(p);
  if (!(std::isfinite(g.x()) && std::isfinite(g.y()))) {
    std::ostringstream out;
    out << "the warp gave a point that is not finite for the world point (" << p.x() << ", "
        << p.y() << ")";
    throw InputError(out.str(), {}, 0, "world_to_grid");
  }
  return g;
}

// Calls on_point(grid point) for the laser origin and every piece end of every usable beam, and
// on_beam_end(is_return) after each beam; the same points in the same order on every call.
template <typename OnStart, typename OnPoint, typename OnBeamEnd>
void trace_beams(const std::vector<SlamMapInput>& scans, const WorldToGrid& world_to_grid,
                 const SlamMapOptions& options, OnStart&& on_start, OnPoint&& on_point,
                 OnBeamEnd&& on_beam_end, std::size_t& used, std::size_t& skipped) {
  used = skipped = 0;
  for (const SlamMapInput& scan : scans) {
    const Eigen::Vector2d origin = scan.laser_pose_in_world.translation();
    std::optional<Eigen::Vector2d> origin_in_grid;
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const std::optional<BeamRay> ray = beam_ray(scan, i, options);
      if (!ray) {
        ++skipped;
        continue;
      }
      ++used;
      if (!origin_in_grid)
        origin_in_grid = checked_warp(world_to_grid, origin);
      on_start(*origin_in_grid);
      const int n = piece_count(ray->length, options.max_piece_length);
      for (int k = 1; k <= n; ++k)
        on_point(checked_warp(world_to_grid, piece_end(origin, *ray, k, n)));
      on_beam_end(ray->is_return);
    }
  }
}

GridGeometry covering_geometry(const Eigen::AlignedBox2d& box, const SlamMapOptions& options) {
  GridGeometry geometry;
  geometry.resolution = options.resolution;
  const double res = options.resolution;
  double corner[2] = {0.0, 0.0};
  double cells[2] = {0.0, 0.0};
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = box.min()[axis] - options.margin;
    double k = std::floor(lo / res);
    while (k * res > lo)  // rounding in k * res must not leave `lo` outside the grid
      k -= 1.0;
    corner[axis] = k * res;
    cells[axis] = std::floor((box.max()[axis] + options.margin - corner[axis]) / res) + 1.0;
  }
  if (cells[0] * cells[1] > static_cast<double>(options.max_cells)) {
    std::ostringstream out;
    out << "the observed area spans " << box.sizes().x() << " x " << box.sizes().y()
        << " m: " << cells[0] << " x " << cells[1] << " cells exceed the limit of "
        << options.max_cells;
    throw InputError(out.str(), {}, 0, "slam_map.max_cells");
  }
  geometry.origin = Pose2{corner[0], corner[1], 0.0};
  geometry.width = static_cast<int>(cells[0]);
  geometry.height = static_cast<int>(cells[1]);
  return geometry;
}

// Scores the cells of one beam: every distinct cell on its way one miss, and its last cell one
// hit (a return) or one more miss (a no-return).
class BeamCellWalker {
 public:
  explicit BeamCellWalker(SlamMapCounts& counts)
      : counts_(counts),
        origin_(counts.geometry.origin.translation()),
        resolution_(counts.geometry.resolution) {}

  void start(const Eigen::Vector2d& point_in_grid) {
    has_pending_ = false;
    at_ = to_cell(point_in_grid);
    visit(cell_x(at_), cell_y(at_));
  }

  // Walks the straight grid line from the current point to `point_in_grid`: a 4-connected DDA
  // taking exactly as many steps as the cells lie apart, so it ends in the end point's cell.
  void line_to(const Eigen::Vector2d& point_in_grid) {
    const Eigen::Vector2d to = to_cell(point_in_grid);
    int ix = cell_x(at_), iy = cell_y(at_);
    const int end_x = cell_x(to), end_y = cell_y(to);
    int left_x = std::abs(end_x - ix), left_y = std::abs(end_y - iy);
    const int step_x = end_x > ix ? 1 : -1, step_y = end_y > iy ? 1 : -1;
    const double dx = to.x() - at_.x(), dy = to.y() - at_.y();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double t_x = left_x > 0 ? (ix + (step_x > 0 ? 1 : 0) - at_.x()) / dx : kInf;
    double t_y = left_y > 0 ? (iy + (step_y > 0 ? 1 : 0) - at_.y()) / dy : kInf;
    const double dt_x = left_x > 0 ? 1.0 / std::abs(dx) : kInf;
    const double dt_y = left_y > 0 ? 1.0 / std::abs(dy) : kInf;
    while (left_x > 0 || left_y > 0) {
      if (left_x > 0 && (left_y == 0 || t_x < t_y)) {
        ix += step_x;
        t_x += dt_x;
        --left_x;
      } else {
        iy += step_y;
        t_y += dt_y;
        --left_y;
      }
      visit(ix, iy);
    }
    at_ = to;
  }

  void finish(bool is_return) {
    if (!has_pending_)
      return;
    if (is_return)
      ++counts_.hits[pending_];
    else
      ++counts_.misses[pending_];
    has_pending_ = false;
  }

 private:
  Eigen::Vector2d to_cell(const Eigen::Vector2d& p) const { return (p - origin_) / resolution_; }
  static int cell_x(const Eigen::Vector2d& c) { return static_cast<int>(std::floor(c.x())); }
  static int cell_y(const Eigen::Vector2d& c) { return static_cast<int>(std::floor(c.y())); }

  // A new cell makes the previous one a miss; the last cell waits for finish().
  void visit(int ix, int iy) {
    if (!counts_.geometry.contains(ix, iy))
      return;  // cannot happen: the grid covers every traced point
    const std::size_t index = static_cast<std::size_t>(iy) * counts_.geometry.width + ix;
    if (has_pending_ && index == pending_)
      return;
    if (has_pending_)
      ++counts_.misses[pending_];
    pending_ = index;
    has_pending_ = true;
  }

  SlamMapCounts& counts_;
  Eigen::Vector2d origin_;
  double resolution_;
  Eigen::Vector2d at_ = Eigen::Vector2d::Zero();  // continuous cell coordinates
  std::size_t pending_ = 0;
  bool has_pending_ = false;
};

}  // namespace

SlamMapInput to_slam_map_input(const SimulatedScan& scan) {
  SlamMapInput input;
  input.laser_pose_in_world = scan.laser_pose_in_world;
  input.start_angle = scan.start_angle;
  input.angle_increment = scan.angle_increment;
  input.max_range = scan.max_range;
  input.ranges.reserve(scan.beams.size());
  for (const SimulatedBeam& beam : scan.beams)
    input.ranges.push_back(beam.reading);
  return input;
}

void validate_slam_map_options(const SlamMapOptions& options) {
  if (!(std::isfinite(options.resolution) && options.resolution > 0.0))
    throw InputError("must be a finite number > 0 " + got(options.resolution), {}, 0,
                     "slam_map.resolution");
  if (!(std::isfinite(options.margin) && options.margin >= 0.0))
    throw InputError("must be a finite number >= 0 " + got(options.margin), {}, 0,
                     "slam_map.margin");
  if (options.min_hits < 1)
    throw InputError("must be >= 1 (got " + std::to_string(options.min_hits) + ")", {}, 0,
                     "slam_map.min_hits");
  if (!(options.occupied_ratio >= 0.0 && options.occupied_ratio <= 1.0))
    throw InputError("must be in [0, 1] " + got(options.occupied_ratio), {}, 0,
                     "slam_map.occupied_ratio");
  if (!(std::isfinite(options.max_piece_length) && options.max_piece_length > 0.0))
    throw InputError("must be a finite number > 0 " + got(options.max_piece_length), {}, 0,
                     "slam_map.max_piece_length");
  if (options.free_range_for_no_return && !(std::isfinite(*options.free_range_for_no_return) &&
                                            *options.free_range_for_no_return > 0.0))
    throw InputError("must be a finite number > 0 " + got(*options.free_range_for_no_return), {}, 0,
                     "slam_map.free_range_for_no_return");
}

SlamMapCounts count_slam_map(const std::vector<SlamMapInput>& scans,
                             const WorldToGrid& world_to_grid, const SlamMapOptions& options) {
  validate_slam_map_options(options);
  SlamMapCounts counts;
  counts.geometry.resolution = options.resolution;

  // Pass 1: the extent of everything traced. Pass 2 maps the same points again rather than
  // storing them (tens of millions of piece ends for a long run).
  Eigen::AlignedBox2d box;
  auto extend = [&](const Eigen::Vector2d& g) { box.extend(g); };
  trace_beams(
      scans, world_to_grid, options, extend, extend, [](bool) {}, counts.beams_used,
      counts.beams_skipped);
  if (box.isEmpty())
    return counts;
  counts.geometry = covering_geometry(box, options);
  counts.hits.assign(counts.geometry.size(), 0);
  counts.misses.assign(counts.geometry.size(), 0);

  BeamCellWalker walker(counts);
  std::size_t used = 0, skipped = 0;
  trace_beams(
      scans, world_to_grid, options, [&](const Eigen::Vector2d& g) { walker.start(g); },
      [&](const Eigen::Vector2d& g) { walker.line_to(g); },
      [&](bool is_return) { walker.finish(is_return); }, used, skipped);
  return counts;
}

OccupancyGrid classify_slam_map(const SlamMapCounts& counts, const SlamMapOptions& options) {
  validate_slam_map_options(options);
  OccupancyGrid grid(counts.geometry, CellState::unknown);
  const GridGeometry& g = counts.geometry;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const std::size_t i = grid.index(ix, iy);
      const double hits = counts.hits[i];
      const double misses = counts.misses[i];
      if (hits >= options.min_hits && hits >= options.occupied_ratio * (hits + misses))
        grid.set_state(ix, iy, CellState::occupied);
      else if (misses > 0)
        grid.set_state(ix, iy, CellState::free);
    }
  }
  return grid;
}

OccupancyGrid build_slam_map(const std::vector<SlamMapInput>& scans,
                             const WorldToGrid& world_to_grid, const SlamMapOptions& options) {
  return classify_slam_map(count_slam_map(scans, world_to_grid, options), options);
}

}  // namespace floorgrid
