#pragma once

// Doors, glass, columns and furniture of a world built from a drawing (internal to
// simulation/).

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/plan_world.hpp"
#include "floorgrid/simulation/room_segmentation.hpp"
#include "floorgrid/simulation/wall_lines.hpp"
#include "floorgrid/simulation/wall_solids.hpp"

namespace floorgrid::plan_world {

/// The world being fitted out: its rasters and what is placed in it.
struct WorldCanvas {
  GridGeometry geometry;       ///< of every mask
  WallSolids solids;           ///< walls the laser sees, inside and outside
  RoomSegmentation rooms;      ///< regions and openings
  cv::Mat glass;               ///< glass panes: the robot stops, the laser passes
  cv::Mat solid;               ///< everything the robot cannot cross: walls, glass, objects
  int start_region = -1;       ///< the region the robot starts in (the largest)
  double clearance = 0.3;      ///< metres the robot's centre keeps from anything solid
  PlanWorld* world = nullptr;  ///< objects, doors and glass walls are added here

  /// Adds an object and marks it solid.
  void add(WorldObject object);
  /// Redraws `solid` from the walls, the glass and the objects (after objects were removed).
  void redraw_solid();
  /// Where the robot's centre can go from the start region (CV_8U); `free_space`, when given,
  /// gets where it could stand, reachable or not.
  cv::Mat reachable_space(cv::Mat* free_space = nullptr) const;
  /// Which regions that space reaches.
  std::vector<char> reachable() const;
  /// Removes the objects `removable` accepts (by their index when this is called) that stand
  /// between the space the robot reaches and space it reached in `before` (but the room
  /// `shut_room`'s), until none is lost or after three rounds; returns the indices removed.
  std::vector<std::size_t> unblock(const cv::Mat& before, int shut_room,
                                   const std::function<bool(std::size_t)>& removable);
};

/// Gives each doorway a leaf (leaf_probability; open, swung into one side, or closed across
/// the opening) and each opening to the outside a closed door or, when wider than a doorway,
/// a glass pane. One room behind a single doorway gets its door closed (a room never
/// visited), others with closed_fraction as long as no more rooms are cut off (counting only
/// openings the robot fits through); leaves that still cut the robot off from space it reached
/// without them, but for that room, are taken off.
void fit_doors(WorldCanvas& canvas, const PlanWorldOptions& options, Random& random);

/// Makes up to max_glass_walls stretches of straight partition glass (inside on both sides,
/// no door or joining wall along them), with mullions every mullion_spacing.
void fit_glass(WorldCanvas& canvas, const cv::Mat& ink, const std::vector<WallLine>& lines,
               const PlanWorldOptions& options, Random& random);

/// Stands columns on a lattice of column_spacing along the building's main direction, where
/// the walls are at least column_clearance away.
void fit_columns(WorldCanvas& canvas, double main_angle, const PlanWorldOptions& options,
                 Random& random);

/// Lines the walls of rooms and corridors with furniture and clutter (cabinets, desks with
/// chairs, shelves, sofas; bins and benches in corridors), and stands tables with chairs in
/// rooms and shelf rows in halls, never within door_keep_free of a doorway and always leaving
/// `passage` free in front. Pieces that cut the robot off from a region it reached before are
/// taken away again.
void furnish(WorldCanvas& canvas, double main_angle, const PlanWorldOptions& options,
             Random& random);

}  // namespace floorgrid::plan_world
