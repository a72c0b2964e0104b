#pragma once

// The inside split into rooms, corridors and halls at its doorways (internal to simulation/).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/simulation/plan_world.hpp"
#include "floorgrid/simulation/wall_solids.hpp"

namespace floorgrid::plan_world {

/// Where two regions (or a region and the outside) meet.
struct Opening {
  int region_a = -1;                                  ///< a region
  int region_b = -1;                                  ///< the other region, or -1 for the outside
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();   ///< on the wall's centre line, world m
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();   ///< unit, along the wall
  Eigen::Vector2d across = Eigen::Vector2d::UnitY();  ///< unit, from region_a to region_b
  Eigen::Vector2d jamb_a = Eigen::Vector2d::Zero();   ///< ends of the opening on that line
  Eigen::Vector2d jamb_b = Eigen::Vector2d::Zero();   ///< (see jamb_a)
  double wall_thickness = 0.0;                        ///< metres, of the wall at its jambs
  bool bounded = false;                               ///< walls were found at both ends
  bool doorway = false;  ///< a doorway's width in a wall, opening up on both sides

  /// The opening's width, metres.
  double width() const { return (jamb_b - jamb_a).norm(); }
};

/// The inside split into regions.
struct RoomSegmentation {
  cv::Mat labels;                    ///< CV_32S: region index per pixel, or -1
  std::vector<WorldRegion> regions;  ///< R1, R2, ... (visited unset)
  std::vector<Opening> openings;     ///< between regions and to the outside
};

/// Splits the inside at its narrow openings: the inside farther than door_core_radius from
/// its edge falls into cores (rooms, corridors, halls), every inside pixel joins the core it
/// reaches first (pieces no core reaches are regions of their own), and where two regions meet
/// is an opening, measured between the walls at its ends. An opening is a doorway when it is
/// doorway_width wide, walled at both ends, and the free space widens on both sides of it.
RoomSegmentation segment_rooms(const WallSolids& solids, const GridGeometry& geometry,
                               const PlanWorldOptions& options);

}  // namespace floorgrid::plan_world
