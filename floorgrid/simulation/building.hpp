#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// What a world segment is; stored in Segment::layer of the world's segments.
enum class SurfaceKind : int {
  wall = 0,       ///< building walls: in the plan (layer WALLS)
  rack = 1,       ///< warehouse racks: in the plan (layer RACKS)
  furniture = 2,  ///< clutter: in the world only
  door_leaf = 3,  ///< open door leaves: in the world; the plan draws doors as swing arcs
  column = 4,     ///< free-standing columns: in the world only (simulate --from-plan)
  mullion = 5,    ///< posts of a glass wall, the only part the laser sees (--from-plan)
};

/// A door: an opening in a wall, with the swing the plan draws.
struct Door {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();      ///< middle of the opening, metres
  Eigen::Vector2d into_room = Eigen::Vector2d::UnitY();  ///< unit normal pointing into the room
  double width = 0.9;                                    ///< clear opening, metres
  double wall_thickness = 0.12;                          ///< of the wall it pierces, metres
};

/// A room of a synthetic building.
struct Room {
  std::string name;              ///< "R01", "office 3", ...
  Eigen::AlignedBox2d interior;  ///< inner wall faces, world metres
  std::vector<Door> doors;       ///< its doors
  bool visited = true;           ///< whether the robot's tour enters it
};

/// A synthetic building in the metric world frame: what the laser sees, what the plan draws,
/// and where the robot can go.
struct Building {
  std::string kind;                             ///< "office" or "warehouse"
  Eigen::AlignedBox2d outline;                  ///< outer faces of the exterior walls, metres
  std::vector<Eigen::AlignedBox2d> wall_boxes;  ///< the solid walls (doors cut out)
  std::vector<Eigen::AlignedBox2d> rack_boxes;  ///< warehouse racks
  std::vector<Segment> walls;                   ///< outline of the wall union: faces seen and drawn
  std::vector<Segment> racks;                   ///< rack outlines
  std::vector<Segment> furniture;               ///< clutter outlines (world only)
  std::vector<Segment> door_leaves;             ///< outlines of the open door leaves (world only)
  std::vector<Arc> door_swings;                 ///< door swing arcs (plan only, layer DOORS)
  std::vector<Segment> door_lines;              ///< door leaf lines (plan only, layer DOORS)
  std::vector<Eigen::Vector2d> wall_corners;    ///< corners of the wall outline (manual pairs)
  std::vector<Room> rooms;                      ///< rooms, visited or not
  std::vector<Eigen::AlignedBox2d> corridors;   ///< corridors and open hall areas
  std::vector<Eigen::Vector2d> tour;            ///< the robot's waypoints, in order
  int rotated_room = -1;  ///< index of the room the gridmap shows rotated, or -1
  Eigen::Vector2d axis_origin = Eigen::Vector2d::Zero();  ///< near end of the long axis
  double axis_angle = 0.0;                                ///< direction of the long axis, radians
  double length = 0.0;                                    ///< along the long axis, metres
  double half_width = 0.0;                                ///< across it, metres

  /// Every surface the laser can hit, tagged with SurfaceKind in Segment::layer.
  std::vector<Segment> world_segments() const;
  /// The plan as drawn, in world metres: layers WALLS, DOORS and RACKS.
  VectorFloorplan plan_in_world() const;
};

/// Which building to make.
struct BuildingOptions {
  std::string kind = "office";  ///< "office" (about 40 x 20 m) or "warehouse" (about 100 x 50 m)
};

/// Generates a building: rooms with doors along corridors (office) or a rack hall with a few
/// offices (warehouse), furniture, door swings, the robot's tour through corridors and into
/// rooms with at least one room never visited, and the room the gridmap will show rotated.
/// Deterministic for a given `random` state.
Building generate_building(const BuildingOptions& options, Random& random);

}  // namespace floorgrid
