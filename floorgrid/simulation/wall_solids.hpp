#pragma once

// The drawing's strokes made solid walls, and the inside told from the outside (internal to
// simulation/). Masks as drawing_raster.hpp describes them.

#include <opencv2/core.hpp>

#include "floorgrid/simulation/plan_world.hpp"

namespace floorgrid::plan_world {

/// How thick the walls drawn as a thin stroke are built, metres.
struct WallThickness {
  double partition = 0.15;  ///< walls between two pieces of inside
  double exterior = 0.35;   ///< walls with the outside on one side
};

/// Solid walls and the free space on either side of them.
struct WallSolids {
  cv::Mat walls;    ///< solid walls
  cv::Mat inside;   ///< free space inside the building
  cv::Mat outside;  ///< known free space outside it
  /// CV_32FC2: at each end of a stroke's centre line, the unit direction (x, y in pixels)
  /// pointing out of the stroke; (0, 0) elsewhere.
  cv::Mat ends;
};

/// The centre line of the strokes: ink pixels at least as far from the paper as their eight
/// neighbours (a one-pixel stroke is all centre).
cv::Mat stroke_centres(const cv::Mat& ink);

/// The ends of the stroke centre lines (see WallSolids::ends): centre pixels whose centre
/// neighbours lie on one straight line on one side of them, pointing along it.
cv::Mat end_directions(const cv::Mat& centres);

/// Makes the strokes solid walls: every stroke centre thinner than the wall it is drawn for
/// grows into a wall of that thickness centred on it (exterior walls the exterior thickness,
/// the others the partition thickness); thicker strokes stay as drawn. Then tells the inside
/// from the outside (see split_inside).
WallSolids build_wall_solids(const cv::Mat& ink, const cv::Mat& unknown,
                             const WallThickness& thickness, double resolution,
                             const PlanWorldOptions& options);

/// Splits the free space (neither wall nor unknown) into inside and outside: the outside is
/// the free space reached from the raster's edge once gaps in the walls narrower than twice
/// `seal_radius` are closed (entrances, open doors), grown back to the walls; pieces of the
/// rest smaller than `min_area` square metres are dropped. Fills `solids.inside` and
/// `solids.outside` from `solids.walls`.
void split_inside(WallSolids& solids, const cv::Mat& unknown, double resolution, double seal_radius,
                  double min_area);

}  // namespace floorgrid::plan_world
