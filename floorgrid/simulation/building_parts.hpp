#pragma once

// Building blocks shared by the office and warehouse generators (internal to simulation/).

#include <Eigen/Geometry>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/building.hpp"

namespace floorgrid::building_parts {

/// An axis-aligned box from its corner coordinates.
Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1);

/// Cuts `openings` out of axis-aligned wall boxes along each wall's long side.
std::vector<Eigen::AlignedBox2d> cut_openings(const std::vector<Eigen::AlignedBox2d>& walls,
                                              const std::vector<Eigen::AlignedBox2d>& openings);

/// A door of `width` in the wall between a room and a corridor: `wall` is the wall box (its
/// thinner side is the thickness), `along` the door centre's coordinate along the wall, and
/// `into_room` the side of the room. Returns the door; `openings` gets the box to cut.
Door make_door(const Eigen::AlignedBox2d& wall, double along, double width,
               const Eigen::Vector2d& into_room, std::vector<Eigen::AlignedBox2d>& openings);

/// Adds a door: its plan symbol (swing arc and leaf line on DOORS, leaf drawn open at 90 degrees
/// into the room, hinged at the opening's left edge as seen from the corridor) and its physical
/// leaf in the world, open against the wall or, when `closed`, shut across the opening (the
/// room behind it then stays unseen from outside).
void add_door(Building& b, const Door& door, bool closed);

/// The four edges of a box as segments of `kind`.
void add_box_outline(std::vector<Segment>& out, const Eigen::AlignedBox2d& box, SurfaceKind kind);
/// A closed regular polygon of `sides` approximating a circle, as segments of `kind`.
void add_circle_outline(std::vector<Segment>& out, const Eigen::Vector2d& center, double radius,
                        int sides, SurfaceKind kind);

/// Places furniture in `area` (a room or corridor interior): cabinets and desks against its
/// walls and free-standing tables and chairs, never within `clearance` of the `keep_free`
/// polyline pieces (the robot's path) nor in `forbidden` boxes (door swings). `density` is the
/// fraction of the wall length to line with furniture. Returns the boxes placed.
struct FurnitureRequest {
  Eigen::AlignedBox2d area;                                            ///< interior to furnish
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> keep_free;  ///< path pieces
  std::vector<Eigen::AlignedBox2d> forbidden;                          ///< door zones and the like
  double clearance = 0.6;                                              ///< metres from the path
  double wall_density = 0.5;  ///< fraction of the walls lined
  int free_standing = 2;      ///< tables/chairs to try
};
void furnish(Building& b, const FurnitureRequest& request, Random& random);

/// How a whole building is furnished: every room lined at 35% with two free-standing pieces,
/// its visit path and every door zone kept free; the corridors (aisles) as given here.
struct CorridorFurnishing {
  double clearance = 0.6;                      ///< metres from the tour
  double wall_density = 0.5;                   ///< fraction of the walls lined
  int free_standing = 2;                       ///< pieces to try per corridor
  std::vector<Eigen::AlignedBox2d> forbidden;  ///< besides the door zones (rack footprints)
};
/// Furnishes every room, then every corridor of `b`, keeping the tour and the doors free.
void furnish_building(Building& b, const CorridorFurnishing& corridors, Random& random);

/// Distance from a box to a segment, metres (0 when they touch or overlap).
double box_segment_distance(const Eigen::AlignedBox2d& box, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& c);

/// The zone a door needs kept free: the opening, the swing of its leaf and an approach in front
/// of it on both sides.
Eigen::AlignedBox2d door_zone(const Door& door);

/// Appends a room visit to the tour: in front of the door, through it, to the room's centre
/// (and a second point in a deep room), and back out.
void visit_room(std::vector<Eigen::Vector2d>& tour, const Room& room, const Door& door);

/// The path pieces of a room visit, for furniture clearance.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> room_visit_path(const Room& room,
                                                                         const Door& door);

/// Finishes a building: cuts the door openings, computes the wall and rack outlines and the
/// wall corners.
void finish_walls(Building& b, const std::vector<Eigen::AlignedBox2d>& openings);

}  // namespace floorgrid::building_parts
