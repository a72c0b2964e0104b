#pragma once

#include <cstdint>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// How the walls a robot inside can see are told from the rest of a drawn plan.
struct VisibleWallsOptions {
  /// Metres: door-sized gaps in the outline (up to twice this) are closed while the outside
  /// is flooded, so an open entrance does not let the outside in.
  double gap_closing = 0.6;
  /// Metres: free space counts as a room, not the hollow of a wall drawn as two lines, when
  /// some cell of it lies at least this far from every wall (a robot fits there).
  double min_clearance = 0.3;
  /// Metres: a wall cell is visible when free room space lies within this distance.
  double reach = 0.1;
  /// Metres: a wall cell farther than `reach` from every room is hidden only within this
  /// distance of one: the far face of a wall whose near face bounds a room. Walls far from
  /// every room stay: the outside may have flooded in through an opening the drawing left (a
  /// corridor drawn open at its end, a gappy outline), and the robot sees those walls.
  double max_thickness = 0.6;
};

/// What visible_walls found.
struct VisibleWalls {
  OccupancyGrid grid;              ///< the plan with every unseen wall cell made unknown
  std::size_t walls = 0;           ///< occupied cells of the plan
  std::size_t hidden = 0;          ///< of which unseen (now unknown)
  std::size_t room_cells = 0;      ///< free cells a robot inside can reach
  std::vector<std::uint8_t> room;  ///< per cell (row-major from the bottom): 1 in a room
  bool applied = false;            ///< false when no inside was found (the plan is unchanged)
};

/// The plan as a robot inside the building sees it. A drawn plan outlines each wall with two
/// lines; a laser only ever meets the face towards the room, but a likelihood field or a scan
/// matcher would as gladly put the endpoints on the far face (the outline's outer line, a
/// wall's hollow), which shifts the robot by a wall's thickness. This finds the rooms (free
/// space not connected to the outside, with room for a robot) and hides the wall cells beyond
/// `reach` of them but within `max_thickness` (they become unknown). A plan without an inside (an
/// outline left open) is returned unchanged. O(cells).
VisibleWalls visible_walls(const OccupancyGrid& plan, const VisibleWallsOptions& options = {});

}  // namespace floorgrid
