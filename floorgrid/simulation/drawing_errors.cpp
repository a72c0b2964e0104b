#include "floorgrid/simulation/drawing_errors.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "floorgrid/simulation/drawing_raster.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr double kAddedDoor = 0.9;  // metres: the door of an added partition

// Sets (or clears) a bar of ink from a to b, `half_width` metres to either side.
void draw_bar(cv::Mat& ink, const GridGeometry& g, const Eigen::Vector2d& a,
              const Eigen::Vector2d& b, double half_width, std::uint8_t value) {
  const double length = (b - a).norm();
  if (length <= 0.0)
    return;
  fill_outline(ink, g, oriented_box((a + b) / 2, (b - a) / length, length, 2.0 * half_width),
               value);
}

// A random order of 0..n-1.
std::vector<std::size_t> shuffled(std::size_t n, Random& random) {
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  for (std::size_t i = n; i > 1; --i)
    std::swap(order[i - 1],
              order[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  return order;
}

// Straight partitions between two pieces of inside, drawn whole, `min`-`max` metres long.
std::vector<WallLine> partitions(const DrawnBuilding& d, double min, double max) {
  std::vector<WallLine> out;
  for (const WallLine& line : d.lines) {
    if (line.length() >= min && line.length() <= max &&
        has_on_both_sides(line, d.solids.inside, d.geometry, 0.3, 0.8) &&
        ink_fraction(line, d.ink, d.geometry, 0.0, line.length()) >= 0.9) {
      out.push_back(line);
    }
  }
  return out;
}

// Erases a wall's stroke but for its ends, which lie in the walls it joins.
void erase_partition(cv::Mat& ink, const GridGeometry& g, const WallLine& line) {
  const Eigen::Vector2d u = line.along();
  const double end = line.half_width + 2 * g.resolution;
  draw_bar(ink, g, line.a + u * end, line.b - u * end, line.half_width + 1.5 * g.resolution, 0);
}

bool move_partition(cv::Mat& ink, const DrawnBuilding& d, const PlanWorldOptions& o, Random& random,
                    std::vector<DrawingError>& errors) {
  const GridGeometry& g = d.geometry;
  const auto candidates = partitions(d, 1.5, 12.0);
  for (const std::size_t i : shuffled(candidates.size(), random)) {
    const WallLine& line = candidates[i];
    const double shift = random.uniform(o.partition_shift.min, o.partition_shift.max);
    const Eigen::Vector2d n = left_of(line.along());
    for (const double sign : {random.bernoulli(0.5) ? 1.0 : -1.0, 0.0}) {
      const double s = sign != 0.0 ? sign : -1.0;  // the other side, second
      bool room = true;
      for (const double t : {0.25, 0.5, 0.75}) {
        const Eigen::Vector2d p = line.a + (line.b - line.a) * t;
        const Eigen::Vector2d start = p + n * s * (line.half_width + g.resolution);
        room = room && run_length(d.solids.inside, g, start, n * s, shift + 0.6) >= shift + 0.6;
      }
      if (!room)
        continue;
      const Eigen::Vector2d offset = n * s * shift;
      const double half = std::max(line.half_width, g.resolution / 2);
      erase_partition(ink, g, line);
      draw_bar(ink, g, line.a + offset, line.b + offset, half, 255);
      draw_bar(ink, g, line.a, line.a + offset, half, 255);
      draw_bar(ink, g, line.b, line.b + offset, half, 255);
      errors.push_back({"partition_moved", line.a, line.b, s * shift});
      return true;
    }
  }
  return false;
}

bool remove_partition(cv::Mat& ink, const DrawnBuilding& d, Random& random,
                      std::vector<DrawingError>& errors) {
  const auto candidates = partitions(d, 2.0, 10.0);
  for (const std::size_t i : shuffled(candidates.size(), random)) {
    const WallLine& line = candidates[i];
    // Not one already changed.
    const bool changed = std::any_of(errors.begin(), errors.end(), [&](const DrawingError& e) {
      return (e.a - line.a).norm() + (e.b - line.b).norm() < 0.5;
    });
    if (changed)
      continue;
    erase_partition(ink, d.geometry, line);
    errors.push_back({"partition_removed", line.a, line.b, 0.0});
    return true;
  }
  return false;
}

bool add_partition(cv::Mat& ink, const DrawnBuilding& d, Random& random,
                   std::vector<DrawingError>& errors) {
  const GridGeometry& g = d.geometry;
  double half = g.resolution / 2;  // the drawing's usual stroke
  if (!d.lines.empty()) {
    std::vector<double> widths;
    for (const WallLine& line : d.lines)
      widths.push_back(line.half_width);
    std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
    half = widths[widths.size() / 2];
  }
  const auto& regions = d.rooms.regions;
  for (const std::size_t r : shuffled(regions.size(), random)) {
    const WorldRegion& region = regions[r];
    if (region.kind == "corridor" || region.area < 15.0)
      continue;
    // The new wall runs across the region's longer side, near its middle.
    const Eigen::Vector2d size = region.box.sizes();
    const Eigen::Vector2d longer =
        size.x() >= size.y() ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY();
    const Eigen::Vector2d across = left_of(longer);
    const Eigen::Vector2d c =
        region.centre + longer * random.uniform(-0.15, 0.15) * size.maxCoeff();
    if (!is_set(d.solids.inside, pixel_of(g, c)))
      continue;
    const double free_before = run_length(d.solids.inside, g, c, -longer, 1.5);
    const double free_after = run_length(d.solids.inside, g, c, longer, 1.5);
    const double r0 = run_length(d.solids.inside, g, c, -across, 30.0);
    const double r1 = run_length(d.solids.inside, g, c, across, 30.0);
    if (free_before < 1.5 || free_after < 1.5 || r0 + r1 < 2.2 || r0 + r1 >= 30.0)
      continue;
    const Eigen::Vector2d e0 = c - across * (r0 + g.resolution);
    const Eigen::Vector2d e1 = c + across * (r1 + g.resolution);
    draw_bar(ink, g, e0, e1, half, 255);
    const double door = random.uniform(0.45 + kAddedDoor / 2, r0 + r1 - 0.45 - kAddedDoor / 2);
    const Eigen::Vector2d door_centre = e0 + across * (g.resolution + door);
    draw_bar(ink, g, door_centre - across * (kAddedDoor / 2),
             door_centre + across * (kAddedDoor / 2), half + 1.5 * g.resolution, 0);
    errors.push_back({"partition_added", e0, e1, 0.0});
    return true;
  }
  return false;
}

bool shift_door(cv::Mat& ink, const DrawnBuilding& d, const PlanWorldOptions& o, Random& random,
                std::vector<DrawingError>& errors) {
  const GridGeometry& g = d.geometry;
  const auto& openings = d.rooms.openings;
  for (const std::size_t i : shuffled(openings.size(), random)) {
    const Opening& op = openings[i];
    if (!op.doorway || op.region_b < 0)
      continue;
    const double width = op.width();
    const double shift =
        (random.bernoulli(0.5) ? 1.0 : -1.0) * random.uniform(o.door_shift.min, o.door_shift.max);
    const Eigen::Vector2d u = op.along * (shift > 0 ? 1.0 : -1.0);
    const double s = std::abs(shift);
    // The wall must go on past the new opening, with inside on both of its sides.
    const WallLine wall{op.centre, op.centre + u * (s + width / 2 + 0.15), 0.0};
    const double from = std::max(width / 2 + g.resolution, s - width / 2);
    const WallLine gap{op.centre + u * (s - width / 2), op.centre + u * (s + width / 2),
                       op.wall_thickness / 2};
    if (ink_fraction(wall, d.ink, g, from, wall.length()) < 0.95 ||
        !has_on_both_sides(gap, d.solids.inside, g, 0.15, 0.9))
      continue;
    // The stroke's half width at the jambs, as drawn.
    const Eigen::Vector2d jamb_wall = op.jamb_b + op.along * 2.0 * g.resolution;
    const double half =
        std::max(g.resolution / 2, (run_length(d.ink, g, jamb_wall, op.across, 1.0) +
                                    run_length(d.ink, g, jamb_wall, -op.across, 1.0)) /
                                       2);
    draw_bar(ink, g, op.jamb_a - op.along * g.resolution, op.jamb_b + op.along * g.resolution, half,
             255);
    draw_bar(ink, g, gap.a, gap.b, half + 2 * g.resolution, 0);
    errors.push_back({"door_shifted", op.centre, op.centre + u * s, shift});
    return true;
  }
  return false;
}

}  // namespace

std::vector<DrawingError> apply_drawing_errors(cv::Mat& ink, const DrawnBuilding& drawn,
                                               const PlanWorldOptions& options, Random& random) {
  std::vector<DrawingError> errors;
  move_partition(ink, drawn, options, random, errors);
  if (random.bernoulli(0.5)) {
    if (!add_partition(ink, drawn, random, errors))
      remove_partition(ink, drawn, random, errors);
  } else if (!remove_partition(ink, drawn, random, errors)) {
    add_partition(ink, drawn, random, errors);
  }
  shift_door(ink, drawn, options, random, errors);
  return errors;
}

}  // namespace floorgrid::plan_world
