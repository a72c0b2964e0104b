#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/simulation/building.hpp"

namespace floorgrid {

struct PlanDrawing;

/// A range [min, max] of a quantity drawn uniformly.
struct UniformRange {
  double min = 0.0;  ///< lower end
  double max = 0.0;  ///< upper end, >= min
};

/// How the world is built from a drawing. Lengths in world metres.
struct PlanWorldOptions {
  double resolution = 0.025;  ///< metres per pixel of the world's raster, at finest
  double max_pixels = 8e6;    ///< the raster is coarsened to stay below this
  double margin = 2.0;        ///< metres of raster around the drawing
  double stroke_join = 0.25;  ///< metres: ink up to twice this apart is one wall
  UniformRange partition_thickness{0.10, 0.20};  ///< of walls drawn as a thin line
  UniformRange exterior_thickness{0.30, 0.45};   ///< of outer walls drawn as a thin line
  double seal_radius = 1.5;        ///< metres: gaps in the outer walls up to twice this are closed
                                   ///< when telling inside from outside
  double min_region_area = 1.0;    ///< square metres: smaller pieces of inside are not rooms
  double door_core_radius = 0.75;  ///< metres: openings narrower than twice this split rooms
  double max_opening = 3.0;        ///< metres: a wall's free end facing a wall this close is a door
  UniformRange doorway_width{0.6, 2.0};    ///< an opening this wide in a wall is a doorway
  double leaf_probability = 0.85;          ///< a doorway has a door leaf
  double closed_fraction = 0.2;            ///< of the doors shut (at least the one room's)
  double leaf_thickness = 0.04;            ///< metres
  int max_glass_walls = 3;                 ///< partition stretches made glass, at most
  UniformRange glass_length{2.0, 5.0};     ///< metres
  double mullion_spacing = 1.25;           ///< metres between a glass wall's mullions
  double column_clearance = 3.0;           ///< metres: columns stand where walls are this far away
  double column_spacing = 6.0;             ///< metres between columns
  UniformRange column_size{0.30, 0.50};    ///< metres, square side or diameter
  double wall_furniture = 0.35;            ///< fraction of a room's walls lined with furniture
  double corridor_furniture = 0.15;        ///< fraction of a corridor's walls lined with clutter
  double passage = 0.9;                    ///< metres furniture always leaves free across a room
  double door_keep_free = 1.0;             ///< metres around a doorway kept free of furniture
  UniformRange partition_shift{0.2, 0.6};  ///< drawing error: a partition moved this far
  UniformRange door_shift{0.3, 1.0};       ///< drawing error: a door moved along its wall
};

/// Something solid the laser sees besides the walls, as a closed outline.
struct WorldObject {
  SurfaceKind kind = SurfaceKind::furniture;  ///< furniture, door_leaf, column or mullion
  std::string what;                           ///< cabinet, desk, chair, table, shelf, ...
  std::vector<Eigen::Vector2d> outline;       ///< corners in order, world metres
  int region = -1;                            ///< the region it stands in, or -1
};

/// An opening in a wall between two regions (or a region and the outside), with its door.
struct WorldDoor {
  Eigen::Vector2d jamb_a = Eigen::Vector2d::Zero();  ///< one end of the opening, world metres
  Eigen::Vector2d jamb_b = Eigen::Vector2d::Zero();  ///< the other end
  std::string state = "none";  ///< open, closed, or none (an opening without a leaf)
  int region_a = -1;           ///< the regions it joins; -1: the outside
  int region_b = -1;           ///< (see region_a)
  /// The width of the opening, metres.
  double width() const { return (jamb_b - jamb_a).norm(); }
};

/// A stretch of partition that is glass in the world: the laser passes, the robot does not.
struct GlassWall {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< one end on the wall's centre line
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< the other end
  double thickness = 0.1;                       ///< metres
  int mullions = 0;                             ///< thin posts the laser sees
};

/// A room, corridor or hall of the world: a piece of its inside between doorways.
struct WorldRegion {
  std::string name;                                  ///< R1, R2, ...
  std::string kind = "room";                         ///< room, corridor or hall
  double area = 0.0;                                 ///< square metres
  Eigen::AlignedBox2d box;                           ///< world metres
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< the point farthest from its walls
  bool visited = false;  ///< the robot's tour enters it (set by the tour)
};

/// A place where the world differs from the drawing (`--drawing-errors some`).
struct DrawingError {
  std::string kind;  ///< partition_moved, partition_added, partition_removed or door_shifted
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< the wall or door as drawn, world metres
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< (the other end)
  double amount = 0.0;  ///< metres moved (0 for an added or removed partition)
};

/// The building built from a drawing: what the laser sees, where the robot can go, and what
/// differs from the drawing. Every coordinate is world metres.
struct PlanWorld {
  double partition_thickness = 0.0;            ///< metres, walls drawn as a thin line
  double exterior_thickness = 0.0;             ///< metres, outer walls drawn as a thin line
  std::vector<Segment> walls;                  ///< faces of the solid walls (SurfaceKind::wall)
  std::vector<WorldObject> objects;            ///< furniture, door leaves, columns, mullions
  std::vector<WorldDoor> doors;                ///< every opening found, with its state
  std::vector<GlassWall> glass;                ///< glass stretches of partitions
  std::vector<WorldRegion> regions;            ///< rooms, corridors and halls
  std::vector<DrawingError> errors;            ///< where the world differs from the drawing
  Eigen::Matrix2Xd drawn_ink;                  ///< the drawing's ink, a point per raster pixel
  std::vector<Eigen::Vector2d> drawn_corners;  ///< corners of the drawing's strokes
  /// The raster the world was built on (yaw 0), and per pixel, row-major from the bottom row:
  GridGeometry raster;
  std::vector<std::uint8_t> walkable;   ///< 1 where the robot's centre may be (ignoring its size)
  std::vector<std::int32_t> region_of;  ///< index into `regions`, or -1

  /// Every surface the laser can hit, tagged with SurfaceKind in Segment::layer.
  std::vector<Segment> world_segments() const;
  /// How many objects of `kind` the world holds.
  std::size_t count(SurfaceKind kind) const;
  /// How many doors are in `state`.
  std::size_t doors_in_state(const std::string& state) const;
};

/// Builds the world from a drawing at `plan_scale` world metres per plan metre: the ink
/// becomes solid walls (a thin stroke a wall of the partition or exterior thickness centred on
/// it, a stroke as thick or thicker kept as drawn), the inside is told from the outside, split
/// into regions at its doorways, doorways get leaves (open, closed or none) and outer openings
/// closed doors, some partition stretches become glass, columns stand in large open areas, and
/// furniture and clutter line the walls and stand in rooms. With `drawing_errors`, a partition
/// is moved, one is added or removed and a door is shifted before the world is built.
/// Furniture never cuts a robot whose centre keeps `robot_clearance` metres from anything
/// solid off from a region it could reach without it.
/// Deterministic for a `random` state. InputError when the drawing has no ink or no inside.
PlanWorld build_plan_world(const PlanDrawing& drawing, double plan_scale,
                           const PlanWorldOptions& options, bool drawing_errors,
                           double robot_clearance, Random& random);

/// The median width of the drawing's doorways at `plan_scale` (metres), or 0 when it has
/// none: what the default plan scale of a vector drawing is bounded by.
double median_doorway_width(const PlanDrawing& drawing, double plan_scale,
                            const PlanWorldOptions& options);

}  // namespace floorgrid
