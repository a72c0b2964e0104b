#pragma once

// Where the world differs from its drawing: small errors of the kind real drawings have
// (internal to simulation/).

#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/plan_world.hpp"
#include "floorgrid/simulation/room_segmentation.hpp"
#include "floorgrid/simulation/wall_lines.hpp"

namespace floorgrid::plan_world {

/// The drawing as its errors are chosen on: its ink, its inside, regions and openings, and
/// its straight walls.
struct DrawnBuilding {
  const cv::Mat& ink;                  ///< the (joined) ink
  const WallSolids& solids;            ///< walls, inside and outside as drawn
  const RoomSegmentation& rooms;       ///< regions and openings as drawn
  const std::vector<WallLine>& lines;  ///< straight walls as drawn
  const GridGeometry& geometry;        ///< of every mask
};

/// Changes `ink` (the world's copy of the drawing's ink) in three places: a partition moved
/// across by partition_shift, a partition the drawing lacks added (with a door) or a drawn one
/// removed, and a doorway shifted along its wall by door_shift. A change is made only where it
/// fits (a moved wall keeps a metre of room, a shifted door stays on its wall); returns the
/// changes made, possibly fewer than three.
std::vector<DrawingError> apply_drawing_errors(cv::Mat& ink, const DrawnBuilding& drawn,
                                               const PlanWorldOptions& options, Random& random);

}  // namespace floorgrid::plan_world
