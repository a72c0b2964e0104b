#include <algorithm>

#include "floorgrid/simulation/building_layouts.hpp"
#include "floorgrid/simulation/building_parts.hpp"

namespace floorgrid {

namespace {

using building_parts::box;

/// A horizontal band of the floor: a row of rooms or a corridor (interior y range).
struct Band {
  double y0 = 0.0, y1 = 0.0;
  bool corridor = false;
};

/// Splits [from, to] into room widths of 3.5 to 6 m.
std::vector<double> room_widths(double from, double to, double wall, Random& random) {
  std::vector<double> widths;
  double left = to - from;
  while (left > 0.0) {
    double w = random.uniform(3.5, 6.0);
    if (left - w - wall < 3.5)
      w = left;  // the last room takes the rest
    widths.push_back(w);
    left -= w + wall;
  }
  return widths;
}

/// The room a waypoint pass along a corridor reaches: rooms sorted by door position.
struct DoorVisit {
  int room = 0;
  int door = 0;
  double x = 0.0;
};

}  // namespace

Building make_office(Random& random) {
  Building b;
  b.kind = "office";
  const double te = 0.3;                         // exterior walls
  const double ti = random.uniform(0.12, 0.16);  // interior walls
  const double length = random.uniform(38.0, 44.0);
  const int corridors = random.bernoulli(0.5) ? 1 : 2;

  // Bands from the bottom: rooms, corridor, rooms[, corridor, rooms].
  std::vector<double> heights;
  if (corridors == 1) {
    const double depth = random.uniform(7.0, 8.5);
    heights = {depth, random.uniform(2.0, 2.6), depth + random.uniform(-0.5, 0.5)};
  } else {
    heights = {random.uniform(4.6, 6.0), random.uniform(2.0, 2.4), random.uniform(4.6, 6.0),
               random.uniform(2.0, 2.4), random.uniform(4.6, 6.0)};
  }
  std::vector<Band> bands;
  double y = te;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    bands.push_back({y, y + heights[i], i % 2 == 1});
    y += heights[i] + (i + 1 < heights.size() ? ti : te);
  }
  const double width = y;
  b.outline = box(0, 0, length, width);
  b.axis_origin = {0.0, width / 2};
  b.axis_angle = 0.0;
  b.length = length;
  b.half_width = width / 2;

  // Exterior walls and the walls between bands.
  b.wall_boxes = {box(0, 0, length, te), box(0, width - te, length, width), box(0, 0, te, width),
                  box(length - te, 0, length, width)};
  std::vector<Eigen::AlignedBox2d> band_walls;  // band_walls[i] lies above band i
  for (std::size_t i = 0; i + 1 < bands.size(); ++i) {
    band_walls.push_back(box(0, bands[i].y1, length, bands[i].y1 + ti));
    b.wall_boxes.push_back(band_walls.back());
  }

  std::vector<Eigen::AlignedBox2d> openings;
  // A connector corridor at the far end joins two corridors through the middle row.
  double connector_x0 = length - te;
  if (corridors == 2) {
    const double cw = random.uniform(2.0, 2.4);
    connector_x0 = length - te - cw;
    const Band& middle = bands[2];
    b.corridors.push_back(box(connector_x0, middle.y0, length - te, middle.y1));
    openings.push_back(box(connector_x0, band_walls[1].min().y() - 0.01, length - te,
                           band_walls[1].max().y() + 0.01));
    openings.push_back(box(connector_x0, band_walls[2].min().y() - 0.01, length - te,
                           band_walls[2].max().y() + 0.01));
  }
  for (const Band& band : bands) {
    if (band.corridor)
      b.corridors.push_back(box(te, band.y0, length - te, band.y1));
  }

  // Rooms: split each room band into rooms with walls between, one door each.
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const Band& band = bands[i];
    if (band.corridor)
      continue;
    const bool middle = corridors == 2 && i == 2;
    const double x_end = middle ? connector_x0 - ti : length - te;
    double x = te;
    const auto widths = room_widths(te, x_end, ti, random);
    for (std::size_t k = 0; k < widths.size(); ++k) {
      Room room;
      room.name = "R" + std::to_string(b.rooms.size() + 1);
      room.interior = box(x, band.y0, x + widths[k], band.y1);
      x += widths[k];
      if (k + 1 < widths.size() || middle) {
        b.wall_boxes.push_back(box(x, band.y0 - ti, x + ti, band.y1 + ti));
        x += ti;
      }
      // The door opens onto the corridor below (into_room +y) or above (into_room -y).
      bool below = i > 0;
      if (i > 0 && i + 1 < bands.size())
        below = random.bernoulli(0.5);
      const Eigen::AlignedBox2d& wall = below ? band_walls[i - 1] : band_walls[i];
      const double door_width = random.uniform(0.8, 1.0);
      const double margin = 0.35 + door_width / 2;
      const double along =
          random.uniform(room.interior.min().x() + margin, room.interior.max().x() - margin);
      room.doors.push_back(building_parts::make_door(wall, along, door_width,
                                                     Eigen::Vector2d(0, below ? 1 : -1), openings));
      b.rooms.push_back(room);
    }
  }
  building_parts::finish_walls(b, openings);

  // Which room the tour skips (never visited, its door shut) and which one the gridmap shows
  // rotated: both away from the tour's start.
  const int n = static_cast<int>(b.rooms.size());
  const int skipped = static_cast<int>(random.integer(n / 3, n - 1));
  b.rooms[static_cast<std::size_t>(skipped)].visited = false;
  do {
    b.rotated_room = static_cast<int>(random.integer(2, n - 1));
  } while (b.rotated_room == skipped);
  for (const Room& room : b.rooms)
    building_parts::add_door(b, room.doors.front(), !room.visited);

  // The tour: along each corridor, into every visited room whose door opens onto it.
  std::vector<std::size_t> corridor_bands;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    if (bands[i].corridor)
      corridor_bands.push_back(i);
  }
  const double connector_x = (connector_x0 + length - te) / 2;
  for (std::size_t c = 0; c < corridor_bands.size(); ++c) {
    const Band& corridor = bands[corridor_bands[c]];
    const double yc = (corridor.y0 + corridor.y1) / 2;
    const bool eastwards = c % 2 == 0;
    std::vector<DoorVisit> visits;
    for (std::size_t r = 0; r < b.rooms.size(); ++r) {
      const Door& door = b.rooms[r].doors.front();
      if (door.center.y() > corridor.y0 - 0.5 && door.center.y() < corridor.y1 + 0.5) {
        visits.push_back({static_cast<int>(r), 0, door.center.x()});
      }
    }
    std::sort(visits.begin(), visits.end(), [&](const DoorVisit& a, const DoorVisit& d) {
      return eastwards ? a.x < d.x : a.x > d.x;
    });
    const double west = te + 0.9, east = (corridors == 2 ? connector_x : length - te - 0.9);
    b.tour.emplace_back(eastwards ? west : east, yc);
    for (const DoorVisit& v : visits) {
      const Room& room = b.rooms[static_cast<std::size_t>(v.room)];
      if (room.visited) {
        building_parts::visit_room(b.tour, room, room.doors.front());
      } else {
        b.tour.emplace_back(v.x, yc);  // passes by the door, looking in
      }
    }
    b.tour.emplace_back(eastwards ? east : west, yc);
  }

  // Furniture: rooms lined with cabinets and desks, a few pieces in the corridors.
  building_parts::furnish_building(
      b, {.clearance = 0.55, .wall_density = 0.15, .free_standing = 1, .forbidden = {}}, random);
  return b;
}

}  // namespace floorgrid
