#include "floorgrid/simulation/building_layouts.hpp"
#include "floorgrid/simulation/building_parts.hpp"

namespace floorgrid {

namespace {
using building_parts::box;
}  // namespace

Building make_warehouse(Random& random) {
  Building b;
  b.kind = "warehouse";
  const double te = 0.3, ti = 0.15;
  const double length = random.uniform(96.0, 104.0);
  const double width = random.uniform(46.0, 54.0);
  b.outline = box(0, 0, length, width);
  b.axis_origin = {0.0, width / 2};
  b.length = length;
  b.half_width = width / 2;
  b.wall_boxes = {box(0, 0, length, te), box(0, width - te, length, width), box(0, 0, te, width),
                  box(length - te, 0, length, width)};

  // A row of offices in the south-west corner, doors onto the main aisle.
  std::vector<Eigen::AlignedBox2d> openings;
  const int offices = static_cast<int>(random.integer(3, 5));
  const double office_depth = random.uniform(5.5, 6.5);
  const double office_top = te + office_depth;
  double x = te;
  std::vector<double> office_x;
  for (int k = 0; k < offices; ++k) {
    const double w = random.uniform(4.5, 6.0);
    office_x.push_back(x);
    x += w;
    office_x.push_back(x);
    b.wall_boxes.push_back(box(x, 0, x + ti, office_top + ti));  // east wall of this office
    x += ti;
  }
  const Eigen::AlignedBox2d office_wall = box(0, office_top, x, office_top + ti);
  b.wall_boxes.push_back(office_wall);
  for (int k = 0; k < offices; ++k) {
    Room room;
    room.name = "office " + std::to_string(k + 1);
    room.interior = box(office_x[2 * k], te, office_x[2 * k + 1], office_top);
    const double door_width = random.uniform(0.9, 1.1);
    const double margin = 0.4 + door_width / 2;
    const double along =
        random.uniform(room.interior.min().x() + margin, room.interior.max().x() - margin);
    room.doors.push_back(building_parts::make_door(office_wall, along, door_width,
                                                   Eigen::Vector2d(0, -1), openings));
    b.rooms.push_back(room);
  }

  // The main aisle across the hall north of the offices; rack rows beyond it, in two blocks
  // split by a cross aisle, with aisles between back-to-back rack pairs.
  const double main_y0 = office_top + ti, main_y1 = main_y0 + random.uniform(4.5, 5.5);
  b.corridors.push_back(box(te, main_y0, length - te, main_y1));
  const double x_r0 = random.uniform(11.0, 14.0), x_r1 = length - random.uniform(7.0, 9.0);
  const double x_mid = (x_r0 + x_r1) / 2 + random.uniform(-5.0, 5.0);
  const double cross = random.uniform(3.2, 3.8);
  const double aisle = random.uniform(3.0, 3.4), pair_depth = 2.3;
  const double y_top = width - te - random.uniform(3.5, 4.5);
  std::vector<double> aisle_y;  // aisle centre lines
  double y = main_y1;
  while (y + pair_depth + aisle <= y_top) {
    b.rack_boxes.push_back(box(x_r0, y, x_mid - cross / 2, y + pair_depth));
    b.rack_boxes.push_back(box(x_mid + cross / 2, y, x_r1, y + pair_depth));
    y += pair_depth;
    aisle_y.push_back(y + aisle / 2);
    b.corridors.push_back(box(x_r0, y, x_r1, y + aisle));
    y += aisle;
  }
  building_parts::finish_walls(b, openings);

  // The tour: the offices first, then a serpentine through the aisles, leaving the last
  // aisles and one office unvisited.
  const double main_yc = (main_y0 + main_y1) / 2;
  const int skipped_office = static_cast<int>(random.integer(1, offices - 1));
  b.rooms[static_cast<std::size_t>(skipped_office)].visited = false;
  do {
    b.rotated_room = static_cast<int>(random.integer(0, offices - 1));
  } while (b.rotated_room == skipped_office);
  for (const Room& room : b.rooms)
    building_parts::add_door(b, room.doors.front(), !room.visited);
  b.tour.emplace_back(te + 1.5, main_yc);
  for (const Room& room : b.rooms) {
    if (room.visited)
      building_parts::visit_room(b.tour, room, room.doors.front());
  }
  const double west = x_r0 - 2.0, east = x_r1 + 2.5;
  b.tour.emplace_back(west, main_yc);
  const std::size_t visited_aisles = aisle_y.size() > 3 ? aisle_y.size() - 2 : aisle_y.size();
  bool at_west = true;
  for (std::size_t i = 0; i < visited_aisles; ++i) {
    b.tour.emplace_back(at_west ? west : east, aisle_y[i]);
    b.tour.emplace_back(at_west ? east : west, aisle_y[i]);
    at_west = !at_west;
  }
  b.corridors.push_back(box(te, main_y1, x_r0, y_top));           // west transverse aisle
  b.corridors.push_back(box(x_r1, main_y1, length - te, y_top));  // east transverse aisle

  // Furniture: pallets staged along the rack faces and walls, desks in the offices.
  building_parts::furnish_building(
      b, {.clearance = 0.9, .wall_density = 0.3, .free_standing = 3, .forbidden = b.rack_boxes},
      random);
  return b;
}

}  // namespace floorgrid
