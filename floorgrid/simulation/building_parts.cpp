#include "floorgrid/simulation/building_parts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/box_union.hpp"

namespace floorgrid::building_parts {

Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(std::min(x0, x1), std::min(y0, y1)),
                             Eigen::Vector2d(std::max(x0, x1), std::max(y0, y1)));
}

std::vector<Eigen::AlignedBox2d> cut_openings(const std::vector<Eigen::AlignedBox2d>& walls,
                                              const std::vector<Eigen::AlignedBox2d>& openings) {
  std::vector<Eigen::AlignedBox2d> out;
  for (const auto& wall : walls) {
    const bool horizontal = wall.sizes().x() >= wall.sizes().y();
    const int along = horizontal ? 0 : 1;
    std::vector<std::pair<double, double>> pieces{{wall.min()[along], wall.max()[along]}};
    for (const auto& opening : openings) {
      const Eigen::AlignedBox2d overlap = wall.intersection(opening);
      if (overlap.isEmpty() || (overlap.sizes().array() <= 0.0).any())
        continue;
      std::vector<std::pair<double, double>> next;
      for (const auto& [a, b] : pieces) {
        const double c0 = opening.min()[along], c1 = opening.max()[along];
        if (c1 <= a || c0 >= b) {
          next.emplace_back(a, b);
          continue;
        }
        if (c0 > a)
          next.emplace_back(a, c0);
        if (c1 < b)
          next.emplace_back(c1, b);
      }
      pieces = next;
    }
    for (const auto& [a, b] : pieces) {
      Eigen::AlignedBox2d piece = wall;
      piece.min()[along] = a;
      piece.max()[along] = b;
      out.push_back(piece);
    }
  }
  return out;
}

Door make_door(const Eigen::AlignedBox2d& wall, double along, double width,
               const Eigen::Vector2d& into_room, std::vector<Eigen::AlignedBox2d>& openings) {
  const bool horizontal = wall.sizes().x() >= wall.sizes().y();
  Door door;
  door.width = width;
  door.into_room = into_room;
  door.wall_thickness = horizontal ? wall.sizes().y() : wall.sizes().x();
  const double eps = 0.01;
  if (horizontal) {
    door.center = {along, wall.center().y()};
    openings.push_back(
        box(along - width / 2, wall.min().y() - eps, along + width / 2, wall.max().y() + eps));
  } else {
    door.center = {wall.center().x(), along};
    openings.push_back(
        box(wall.min().x() - eps, along - width / 2, wall.max().x() + eps, along + width / 2));
  }
  return door;
}

namespace {
Eigen::Vector2d left_of(const Eigen::Vector2d& n) {
  return {-n.y(), n.x()};
}
}  // namespace

void add_door(Building& b, const Door& door, bool closed) {
  const Eigen::Vector2d n = door.into_room;
  const Eigen::Vector2d hinge =
      door.center + n * (door.wall_thickness / 2) + left_of(n) * (door.width / 2);
  const double open_angle = std::atan2(n.y(), n.x());
  // Closed, the leaf points from the hinge across the opening (-left); open, into the room (n).
  b.door_swings.push_back({hinge, door.width, open_angle - std::numbers::pi / 2, open_angle,
                           static_cast<int>(SurfaceKind::door_leaf)});
  b.door_lines.push_back({hinge, hinge + n * door.width, static_cast<int>(SurfaceKind::door_leaf)});
  // The physical leaf, 4 cm thick: open, against the hinge side of the opening; closed, across
  // the opening on the room side.
  Eigen::AlignedBox2d leaf(hinge);
  if (closed) {
    leaf.extend(hinge - left_of(n) * door.width - n * 0.04);
  } else {
    leaf.extend(hinge + left_of(n) * 0.04 + n * door.width);
  }
  add_box_outline(b.door_leaves, leaf, SurfaceKind::door_leaf);
}

void add_box_outline(std::vector<Segment>& out, const Eigen::AlignedBox2d& bx, SurfaceKind kind) {
  const int k = static_cast<int>(kind);
  const Eigen::Vector2d p0 = bx.min(), p2 = bx.max();
  const Eigen::Vector2d p1(p2.x(), p0.y()), p3(p0.x(), p2.y());
  out.push_back({p0, p1, k});
  out.push_back({p1, p2, k});
  out.push_back({p2, p3, k});
  out.push_back({p3, p0, k});
}

void add_circle_outline(std::vector<Segment>& out, const Eigen::Vector2d& center, double radius,
                        int sides, SurfaceKind kind) {
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2 * std::numbers::pi * i / sides, a1 = 2 * std::numbers::pi * (i + 1) / sides;
    out.push_back({center + radius * Eigen::Vector2d(std::cos(a0), std::sin(a0)),
                   center + radius * Eigen::Vector2d(std::cos(a1), std::sin(a1)),
                   static_cast<int>(kind)});
  }
}

double box_segment_distance(const Eigen::AlignedBox2d& bx, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& c) {
  // The segment crosses the box when sampled densely enough; otherwise the nearest features are
  // an endpoint against the box or a box corner against the segment.
  const Eigen::Vector2d d = c - a;
  const int steps = std::max(1, static_cast<int>(d.norm() / 0.05));
  for (int i = 0; i <= steps; ++i) {
    if (bx.contains(a + d * (double(i) / steps)))
      return 0.0;
  }
  double best = std::min(bx.exteriorDistance(a), bx.exteriorDistance(c));
  const Segment s{a, c, 0};
  for (const auto corner : {Eigen::AlignedBox2d::BottomLeft, Eigen::AlignedBox2d::BottomRight,
                            Eigen::AlignedBox2d::TopLeft, Eigen::AlignedBox2d::TopRight}) {
    best = std::min(best, distance_to_segment(bx.corner(corner), s));
  }
  return best;
}

Eigen::AlignedBox2d door_zone(const Door& door) {
  const Eigen::Vector2d n = door.into_room, l = left_of(n);
  Eigen::AlignedBox2d zone;
  const double half = door.width / 2 + 0.3;
  for (const double side : {-1.0, 1.0}) {
    zone.extend(door.center + l * half * side - n * (door.wall_thickness / 2 + 1.0));
    zone.extend(door.center + l * half * side + n * (door.wall_thickness / 2 + door.width + 0.3));
  }
  return zone;
}

namespace {
std::vector<Eigen::Vector2d> visit_points(const Room& room, const Door& door) {
  const Eigen::Vector2d n = door.into_room;
  const Eigen::Vector2d outer = door.center - n * (door.wall_thickness / 2 + 0.9);
  // Inside, first go straight past the open leaf before turning towards the centre.
  const Eigen::Vector2d inner = door.center + n * (door.wall_thickness / 2 + door.width + 0.4);
  const Eigen::Vector2d centre = room.interior.center();
  const double depth = std::abs(room.interior.sizes().dot(n));
  std::vector<Eigen::Vector2d> points{outer, inner, centre};
  // In a deep room, also go towards its far wall.
  if (depth > 6.5)
    points.push_back(centre + n * (depth / 2 - 1.5));
  points.push_back(inner);
  points.push_back(outer);
  return points;
}
}  // namespace

void visit_room(std::vector<Eigen::Vector2d>& tour, const Room& room, const Door& door) {
  for (const auto& p : visit_points(room, door))
    tour.push_back(p);
}

std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> room_visit_path(const Room& room,
                                                                         const Door& door) {
  const auto points = visit_points(room, door);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pieces;
  for (std::size_t i = 1; i < points.size(); ++i)
    pieces.emplace_back(points[i - 1], points[i]);
  return pieces;
}

namespace {

bool clear_of(const Eigen::AlignedBox2d& candidate, const FurnitureRequest& request,
              const std::vector<Eigen::AlignedBox2d>& placed) {
  if (!request.area.contains(candidate))
    return false;
  for (const auto& f : request.forbidden) {
    if (!f.intersection(candidate).isEmpty())
      return false;
  }
  for (const auto& p : placed) {
    Eigen::AlignedBox2d grown = p;
    grown.min().array() -= 0.1;
    grown.max().array() += 0.1;
    if (!grown.intersection(candidate).isEmpty())
      return false;
  }
  for (const auto& [a, c] : request.keep_free) {
    if (box_segment_distance(candidate, a, c) < request.clearance)
      return false;
  }
  return true;
}

}  // namespace

void furnish(Building& b, const FurnitureRequest& request, Random& random) {
  std::vector<Eigen::AlignedBox2d> placed;
  const Eigen::AlignedBox2d& area = request.area;
  const double inset = 0.02;  // furniture stands a little off the wall face
  // Along each of the four walls: runs of cabinets and desks separated by gaps.
  for (int side = 0; side < 4; ++side) {
    const bool horizontal = side < 2;  // 0 bottom, 1 top, 2 left, 3 right
    const double from = horizontal ? area.min().x() : area.min().y();
    const double to = horizontal ? area.max().x() : area.max().y();
    double pos = from + random.uniform(0.0, 0.6);
    while (pos < to - 0.6) {
      const bool desk = random.bernoulli(0.35);
      const double length = random.uniform(0.8, desk ? 1.8 : 2.2);
      const double depth = desk ? random.uniform(0.65, 0.8) : random.uniform(0.35, 0.6);
      const bool place = random.bernoulli(request.wall_density);
      if (place && pos + length < to) {
        Eigen::AlignedBox2d candidate;
        if (side == 0)
          candidate =
              box(pos, area.min().y() + inset, pos + length, area.min().y() + inset + depth);
        if (side == 1)
          candidate =
              box(pos, area.max().y() - inset - depth, pos + length, area.max().y() - inset);
        if (side == 2)
          candidate =
              box(area.min().x() + inset, pos, area.min().x() + inset + depth, pos + length);
        if (side == 3)
          candidate =
              box(area.max().x() - inset - depth, pos, area.max().x() - inset, pos + length);
        if (clear_of(candidate, request, placed)) {
          placed.push_back(candidate);
          add_box_outline(b.furniture, candidate, SurfaceKind::furniture);
          // A chair in front of a desk.
          if (desk && random.bernoulli(0.7)) {
            const Eigen::Vector2d centre = candidate.center();
            Eigen::Vector2d chair = centre;
            const double out = depth / 2 + 0.45;
            if (side == 0)
              chair.y() += out;
            if (side == 1)
              chair.y() -= out;
            if (side == 2)
              chair.x() += out;
            if (side == 3)
              chair.x() -= out;
            const Eigen::AlignedBox2d c =
                box(chair.x() - 0.23, chair.y() - 0.23, chair.x() + 0.23, chair.y() + 0.23);
            if (clear_of(c, request, placed)) {
              placed.push_back(c);
              add_box_outline(b.furniture, c, SurfaceKind::furniture);
            }
          }
        }
      }
      pos += length + random.uniform(0.1, 1.2);
    }
  }
  // Free-standing tables (round or square) and stools.
  for (int i = 0; i < request.free_standing; ++i) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const bool round = random.bernoulli(0.5);
      const double r = round ? random.uniform(0.35, 0.6) : random.uniform(0.4, 0.7);
      const Eigen::Vector2d c(random.uniform(area.min().x() + r, area.max().x() - r),
                              random.uniform(area.min().y() + r, area.max().y() - r));
      const Eigen::AlignedBox2d candidate = box(c.x() - r, c.y() - r, c.x() + r, c.y() + r);
      if (!clear_of(candidate, request, placed))
        continue;
      placed.push_back(candidate);
      if (round) {
        add_circle_outline(b.furniture, c, r, 12, SurfaceKind::furniture);
      } else {
        add_box_outline(b.furniture, candidate, SurfaceKind::furniture);
      }
      break;
    }
  }
}

void finish_walls(Building& b, const std::vector<Eigen::AlignedBox2d>& openings) {
  b.wall_boxes = cut_openings(b.wall_boxes, openings);
  const BoxUnionOutline walls = box_union_outline(b.wall_boxes);
  b.walls = walls.edges;
  for (Segment& s : b.walls)
    s.layer = static_cast<int>(SurfaceKind::wall);
  b.wall_corners = walls.corners;
  b.racks.clear();
  for (const auto& r : b.rack_boxes)
    add_box_outline(b.racks, r, SurfaceKind::rack);
}

void furnish_building(Building& b, const CorridorFurnishing& corridors, Random& random) {
  std::vector<Eigen::AlignedBox2d> zones;
  for (const Room& room : b.rooms)
    zones.push_back(door_zone(room.doors.front()));
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> tour_pieces;
  for (std::size_t i = 1; i < b.tour.size(); ++i)
    tour_pieces.emplace_back(b.tour[i - 1], b.tour[i]);
  for (const Room& room : b.rooms) {
    FurnitureRequest request;
    request.area = room.interior;
    request.keep_free = room_visit_path(room, room.doors.front());
    request.forbidden = zones;
    request.wall_density = 0.35;
    request.free_standing = 2;
    furnish(b, request, random);
  }
  for (const auto& corridor : b.corridors) {
    FurnitureRequest request;
    request.area = corridor;
    request.keep_free = tour_pieces;
    request.forbidden = zones;
    request.forbidden.insert(request.forbidden.end(), corridors.forbidden.begin(),
                             corridors.forbidden.end());
    request.clearance = corridors.clearance;
    request.wall_density = corridors.wall_density;
    request.free_standing = corridors.free_standing;
    furnish(b, request, random);
  }
}

}  // namespace floorgrid::building_parts
