#include "floorgrid/simulation/world_fittings.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>

#include "floorgrid/simulation/drawing_raster.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kGlassThickness = 0.05;  // metres: a pane sealing a wide outer opening
constexpr double kMullionWidth = 0.06;    // metres along the glass
constexpr double kDoubleDoor = 1.25;      // metres: wider doorways have a pair of leaves
constexpr double kMargin = 0.1;           // metres a robot needs beyond its clearance to pass

// Which regions the start reaches through the openings not in `closed` (by the openings'
// graph, not yet by a robot's size).
std::vector<char> reached_through(const WorldCanvas& c, const std::set<std::size_t>& closed) {
  std::vector<char> seen(c.rooms.regions.size(), 0);
  if (c.start_region < 0)
    return seen;
  std::vector<int> stack{c.start_region};
  seen[static_cast<std::size_t>(c.start_region)] = 1;
  while (!stack.empty()) {
    const int r = stack.back();
    stack.pop_back();
    for (std::size_t i = 0; i < c.rooms.openings.size(); ++i) {
      const Opening& op = c.rooms.openings[i];
      // (A gap the robot does not fit through is no way in.)
      if (closed.count(i) || op.region_b < 0 || (op.region_a != r && op.region_b != r) ||
          op.width() < 2 * c.clearance + kMargin)
        continue;
      const int other = op.region_a == r ? op.region_b : op.region_a;
      if (!seen[static_cast<std::size_t>(other)]) {
        seen[static_cast<std::size_t>(other)] = 1;
        stack.push_back(other);
      }
    }
  }
  return seen;
}

// How many regions the start reaches through the openings not in `closed`.
std::size_t reachable(const WorldCanvas& c, const std::set<std::size_t>& closed) {
  const std::vector<char> seen = reached_through(c, closed);
  return static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 1));
}

// Which doorways get a closed leaf: first one whose closing cuts off exactly one room (a
// room never visited: `shut_room`, or -1), then others that cut off no more.
std::set<std::size_t> choose_closed(const WorldCanvas& c, const std::vector<std::size_t>& leaves,
                                    double fraction, Random& random, int& shut_room) {
  std::set<std::size_t> closed;
  std::vector<std::size_t> order = leaves;
  for (std::size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1],
              order[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  // The one room never visited: among the doors that cut off exactly one room, that of one of
  // the three smallest rooms.
  const std::size_t all = reachable(c, closed);
  std::vector<std::pair<double, std::size_t>> cutting;
  for (const std::size_t i : order) {
    const Opening& op = c.rooms.openings[i];
    const auto kind = [&](int r) { return c.rooms.regions[static_cast<std::size_t>(r)].kind; };
    if (kind(op.region_a) != "room" && kind(op.region_b) != "room")
      continue;
    closed.insert(i);
    if (reachable(c, closed) + 1 == all) {
      const double area = std::min(c.rooms.regions[static_cast<std::size_t>(op.region_a)].area,
                                   c.rooms.regions[static_cast<std::size_t>(op.region_b)].area);
      cutting.emplace_back(area, i);
    }
    closed.erase(i);
  }
  std::sort(cutting.begin(), cutting.end());
  shut_room = -1;
  if (!cutting.empty()) {
    const auto pick =
        random.integer(0, std::min<std::int64_t>(2, std::int64_t(cutting.size()) - 1));
    const std::size_t door = cutting[static_cast<std::size_t>(pick)].second;
    closed.insert(door);
    // The room cut off is the one the start no longer reaches.
    const Opening& op = c.rooms.openings[door];
    shut_room = reached_through(c, {door})[static_cast<std::size_t>(op.region_a)] ? op.region_b
                                                                                  : op.region_a;
  }
  const std::size_t floor = reachable(c, closed);
  for (const std::size_t i : order) {
    if (closed.count(i) || !random.bernoulli(fraction))
      continue;
    closed.insert(i);
    if (reachable(c, closed) < floor)
      closed.erase(i);
  }
  return closed;
}

// An open leaf `width` wide: hinged on one jamb at the wall's face on `side`, swung `angle`
// from shut.
std::vector<Eigen::Vector2d> open_leaf(const Opening& op, bool hinge_b, double side, double angle,
                                       double thickness, double width) {
  const Eigen::Vector2d to_hinge = hinge_b ? op.along : -op.along;
  const Eigen::Vector2d hinge =
      (hinge_b ? op.jamb_b : op.jamb_a) + op.across * side * (op.wall_thickness / 2 + 0.005);
  const Eigen::Vector2d d =
      -to_hinge * std::cos(angle) + op.across * side * std::sin(angle);  // along the leaf
  Eigen::Vector2d e = left_of(d);
  if (e.dot(to_hinge) < 0.0)
    e = -e;
  return {hinge, hinge + d * width, hinge + d * width + e * thickness, hinge + e * thickness};
}

void add_glass(WorldCanvas& c, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness,
               const PlanWorldOptions& o) {
  const double length = (b - a).norm();
  const Eigen::Vector2d u = (b - a) / length;
  const std::vector<Eigen::Vector2d> pane = oriented_box((a + b) / 2, u, length, thickness);
  cv::Mat cut(c.solid.size(), CV_8UC1, cv::Scalar(0));
  fill_outline(cut, c.geometry, pane);
  cv::bitwise_or(c.glass, cut, c.glass);
  cv::bitwise_or(c.solid, cut, c.solid);
  cv::Mat keep;
  cv::bitwise_not(cut, keep);
  cv::bitwise_and(c.solids.walls, keep, c.solids.walls);
  GlassWall glass{a, b, thickness, 0};
  const int mullions = static_cast<int>(std::floor(length / o.mullion_spacing));
  for (int i = 1; i <= mullions; ++i) {
    const Eigen::Vector2d p = a + u * (length * i / (mullions + 1));
    c.add({SurfaceKind::mullion, "mullion", oriented_box(p, u, kMullionWidth, thickness), -1});
    ++glass.mullions;
  }
  c.world->glass.push_back(glass);
}

}  // namespace

void WorldCanvas::add(WorldObject object) {
  fill_outline(solid, geometry, object.outline);
  world->objects.push_back(std::move(object));
}

void WorldCanvas::redraw_solid() {
  cv::bitwise_or(solids.walls, glass, solid);
  for (const WorldObject& object : world->objects)
    fill_outline(solid, geometry, object.outline);
}

cv::Mat WorldCanvas::reachable_space(cv::Mat* free_space) const {
  cv::Mat walkable;
  cv::bitwise_not(solid, walkable);
  cv::bitwise_and(walkable, solids.inside, walkable);
  cv::Mat room, free, labels;
  cv::distanceTransform(walkable, room, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::compare(room, clearance / geometry.resolution + 0.5, free, cv::CMP_GT);
  const int count = cv::connectedComponents(free, labels, 8, CV_32S);
  // The robot's piece: the one most of the start region lies in.
  std::vector<std::size_t> in_start(static_cast<std::size_t>(count), 0);
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      if (rooms.labels.at<int>(y, x) == start_region)
        ++in_start[static_cast<std::size_t>(labels.at<int>(y, x))];
    }
  }
  in_start[0] = 0;
  const auto home =
      static_cast<int>(std::max_element(in_start.begin(), in_start.end()) - in_start.begin());
  cv::Mat space = labels == home;
  if (home == 0)
    space.setTo(0);
  if (free_space != nullptr)
    *free_space = free;
  return space;
}

std::vector<std::size_t> WorldCanvas::unblock(const cv::Mat& before, int shut_room,
                                              const std::function<bool(std::size_t)>& removable) {
  std::vector<std::size_t> original(world->objects.size()), removed;
  std::iota(original.begin(), original.end(), std::size_t{0});
  const double reach = clearance / geometry.resolution + 2.0;
  for (int round = 0; round < 3; ++round) {
    cv::Mat free;
    const cv::Mat now = reachable_space(&free);
    cv::Mat lost = before & free & ~now;
    if (shut_room >= 0)
      lost.setTo(0, rooms.labels == shut_room);
    if (cv::countNonZero(lost) == 0)
      break;
    // Between the two: within the robot's clearance of both.
    cv::Mat near_lost, near_now;
    cv::compare(distance_to(lost), reach, near_lost, cv::CMP_LE);
    cv::compare(distance_to(now), reach, near_now, cv::CMP_LE);
    std::vector<char> drop(world->objects.size(), 0);
    for (std::size_t k = 0; k < drop.size(); ++k) {
      const auto& outline = world->objects[k].outline;
      drop[k] = removable(original[k]) && outline_pixels(near_lost, geometry, outline).second > 0 &&
                outline_pixels(near_now, geometry, outline).second > 0;
    }
    if (std::count(drop.begin(), drop.end(), 1) == 0)
      break;
    std::vector<WorldObject> kept;
    std::vector<std::size_t> kept_original;
    for (std::size_t k = 0; k < drop.size(); ++k) {
      if (drop[k]) {
        removed.push_back(original[k]);
        continue;
      }
      kept.push_back(std::move(world->objects[k]));
      kept_original.push_back(original[k]);
    }
    world->objects = std::move(kept);
    original = std::move(kept_original);
    redraw_solid();
  }
  return removed;
}

std::vector<char> WorldCanvas::reachable() const {
  const cv::Mat space = reachable_space();
  std::vector<char> reached(rooms.regions.size(), 0);
  for (int y = 0; y < space.rows; ++y) {
    for (int x = 0; x < space.cols; ++x) {
      const int r = rooms.labels.at<int>(y, x);
      if (r >= 0 && space.at<std::uint8_t>(y, x))
        reached[static_cast<std::size_t>(r)] = 1;
    }
  }
  return reached;
}

void fit_doors(WorldCanvas& c, const PlanWorldOptions& o, Random& random) {
  const auto& openings = c.rooms.openings;
  const cv::Mat before = c.reachable_space();
  std::vector<std::pair<std::size_t, std::size_t>> leaf_of;  // object index, door index
  int shut_door = -1;
  std::vector<std::size_t> leaves;
  std::vector<char> has_leaf(openings.size(), 0);
  for (std::size_t i = 0; i < openings.size(); ++i) {
    if (openings[i].doorway && openings[i].region_b >= 0 && random.bernoulli(o.leaf_probability)) {
      leaves.push_back(i);
      has_leaf[i] = 1;
    }
  }
  int shut_room = -1;
  const std::set<std::size_t> closed =
      choose_closed(c, leaves, o.closed_fraction, random, shut_room);
  for (std::size_t i = 0; i < openings.size(); ++i) {
    const Opening& op = openings[i];
    WorldDoor door{op.jamb_a, op.jamb_b, "none", op.region_a, op.region_b};
    if (op.region_b < 0) {
      // An opening to the outside is sealed: a shut door, or a window (glass the laser sees
      // through) half the time and always when wider than a door.
      if (!op.bounded)
        continue;
      if (op.width() > o.doorway_width.max || random.bernoulli(0.5)) {
        add_glass(c, op.jamb_a, op.jamb_b, kGlassThickness, o);
        continue;
      }
      door.state = "closed";
    } else if (!op.doorway) {
      continue;
    } else if (has_leaf[i]) {
      door.state = closed.count(i) ? "closed" : "open";
    }
    // A wide opening has a pair of leaves meeting in the middle.
    const bool pair = op.width() > kDoubleDoor;
    const double leaf = pair ? op.width() / 2 : op.width();
    if (door.state == "open") {
      // Swung about 90 degrees into a side where the leaves fit (a room rather than a corridor
      // or hall); a leaf that fits nowhere is taken off.
      const double angle = random.uniform(80.0, 100.0) * kDegree;
      const bool hinge_b = random.bernoulli(0.5);
      const auto& regions = c.rooms.regions;
      const bool a_room = regions[static_cast<std::size_t>(op.region_a)].kind == "room";
      const bool b_room = regions[static_cast<std::size_t>(op.region_b)].kind == "room";
      // `across` points from region a to region b.
      const double side =
          a_room == b_room ? (random.bernoulli(0.5) ? 1.0 : -1.0) : (b_room ? 1.0 : -1.0);
      door.state = "none";
      for (int k = 0; k < 4 && door.state == "none"; ++k) {
        std::vector<std::vector<Eigen::Vector2d>> swung;
        for (const bool b : pair ? std::vector<bool>{false, true}
                                 : std::vector<bool>{(k & 1) ? !hinge_b : hinge_b}) {
          swung.push_back(open_leaf(op, b, (k & 2) ? -side : side, angle, o.leaf_thickness, leaf));
        }
        const bool fit = std::all_of(swung.begin(), swung.end(), [&](const auto& outline) {
          const auto [pixels, blocked] = outline_pixels(c.solid, c.geometry, outline);
          const auto [all, inside] = outline_pixels(c.solids.inside, c.geometry, outline);
          return blocked <= 0.05 * pixels && inside >= 0.9 * all;
        });
        if (!fit)
          continue;
        for (auto& outline : swung) {
          leaf_of.emplace_back(c.world->objects.size(), c.world->doors.size());
          c.add({SurfaceKind::door_leaf, "door", std::move(outline), op.region_a});
        }
        door.state = "open";
      }
    }
    if (door.state == "closed") {
      for (const double offset :
           pair ? std::vector<double>{-0.25, 0.25} : std::vector<double>{0.0}) {
        leaf_of.emplace_back(c.world->objects.size(), c.world->doors.size());
        c.add({SurfaceKind::door_leaf, "door",
               oriented_box(op.centre + op.along * (offset * op.width()), op.along, leaf,
                            o.leaf_thickness),
               op.region_a});
      }
    }
    if (closed.count(i) && (op.region_a == shut_room || op.region_b == shut_room))
      shut_door = static_cast<int>(c.world->doors.size());
    c.world->doors.push_back(door);
  }
  // Leaves (but the shut room's) between the robot and space it reached without them go.
  std::vector<int> door_of_object(c.world->objects.size(), -1);
  for (const auto& [object, door] : leaf_of)
    door_of_object[object] = static_cast<int>(door);
  const auto removed = c.unblock(before, shut_room, [&](std::size_t k) {
    return door_of_object[k] >= 0 && door_of_object[k] != shut_door;
  });
  for (const std::size_t k : removed)
    c.world->doors[static_cast<std::size_t>(door_of_object[k])].state = "none";
}

void fit_glass(WorldCanvas& c, const cv::Mat& ink, const std::vector<WallLine>& lines,
               const PlanWorldOptions& o, Random& random) {
  const GridGeometry& g = c.geometry;
  const int wanted = static_cast<int>(random.integer(1, std::max(1, o.max_glass_walls)));
  std::vector<std::size_t> order(lines.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  for (std::size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1],
              order[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  int made = 0;
  for (const std::size_t i : order) {
    if (made >= wanted)
      break;
    const WallLine& line = lines[i];
    const double length = line.length();
    if (length < o.glass_length.min + 0.6 || ink_fraction(line, ink, g, 0.0, length) < 0.95)
      continue;
    const double stretch =
        std::min(random.uniform(o.glass_length.min, o.glass_length.max), length - 0.6);
    const double start = random.uniform(0.3, length - 0.3 - stretch);
    const Eigen::Vector2d u = line.along(), n = left_of(u);
    const WallLine pane{line.a + u * start, line.a + u * (start + stretch), line.half_width};
    const Eigen::Vector2d mid = (pane.a + pane.b) / 2;
    const double thickness =
        run_length(c.solids.walls, g, mid, n, 1.0) + run_length(c.solids.walls, g, mid, -n, 1.0);
    const bool apart =
        std::none_of(c.world->glass.begin(), c.world->glass.end(),
                     [&](const GlassWall& w) { return (w.a + w.b - 2 * mid).norm() < 2.0; });
    if (!apart || thickness <= 0.0 ||
        !has_on_both_sides({pane.a, pane.b, thickness / 2}, c.solids.inside, g, 0.1, 1.0))
      continue;
    add_glass(c, pane.a, pane.b, thickness + 2 * g.resolution, o);
    ++made;
  }
}

void fit_columns(WorldCanvas& c, double main_angle, const PlanWorldOptions& o, Random& random) {
  const GridGeometry& g = c.geometry;
  cv::Mat depth;
  cv::distanceTransform(c.solids.inside, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::Mat open;
  cv::compare(depth, o.column_clearance / g.resolution, open, cv::CMP_GE);
  if (cv::countNonZero(open) == 0)
    return;
  const Eigen::Vector2d u(std::cos(main_angle), std::sin(main_angle)), v = left_of(u);
  Eigen::AlignedBox2d extent;  // of the open area, in lattice coordinates
  const Eigen::Matrix2Xd points = set_pixels(open, g);
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    extent.extend(Eigen::Vector2d(points.col(i).dot(u), points.col(i).dot(v)));
  const double s = o.column_spacing;
  const Eigen::Vector2d phase(random.uniform(0.0, s), random.uniform(0.0, s));
  const bool round = random.bernoulli(0.3);
  const double size = random.uniform(o.column_size.min, o.column_size.max);
  constexpr int kMaxColumns = 40;
  int made = 0;
  for (double a = std::floor(extent.min().x() / s) * s + phase.x(); a <= extent.max().x(); a += s) {
    for (double b = std::floor(extent.min().y() / s) * s + phase.y(); b <= extent.max().y();
         b += s) {
      const Eigen::Vector2d p = u * a + v * b;
      if (made >= kMaxColumns || !is_set(open, pixel_of(g, p)))
        continue;
      const cv::Point px = pixel_of(g, p);
      const int region = c.rooms.labels.at<int>(px);
      c.add({SurfaceKind::column, "column",
             round ? circle_outline(p, size / 2, 16) : oriented_box(p, u, size, size), region});
      ++made;
    }
  }
}

}  // namespace floorgrid::plan_world
