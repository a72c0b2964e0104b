#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_fit_score.hpp"

namespace floorgrid {

/// Where the laser meets a wall drawn as a line. An architect's drawing often draws a wall as
/// one stroke along its middle; the laser sees its faces, half the wall's thickness off the
/// stroke on either side. A partition's two faces lie symmetrically about the stroke, so they
/// shift no global fit; an outer wall shows only its inner face, so fitting the gridmap's outline
/// onto the drawn outline stretches it by the outer wall's thickness, and the plan scale comes
/// out low by about that thickness over the building's extent (measured on drawings made into
/// worlds, simulate --from-plan: 0.4-1.4% low). The registration is therefore refined with the
/// two offsets as unknowns: one for the faces of walls with the building's outside behind them,
/// one for the rest.
struct WallFaceOptions {
  /// Refine the registration with the faces' offsets (raster drawings). On the drawings of
  /// bench/real_matrix.sh where it was used, the plan scale error went from -0.5% to -2.1% to
  /// between -0.5% and +0.24% (README: "The outer walls' faces").
  bool enabled = true;
  /// World metres: gaps up to twice this in the drawing's outer walls (entrances, open doors)
  /// are closed when telling the building's outside from its inside.
  double seal_radius = 1.0;
  /// World metres: behind a wall surface, the outside is looked for this deep (a wall drawn
  /// thicker is not looked through).
  double max_depth = 0.6;
  double radius = 0.3;  ///< world metres: a gridmap wall point matched to a plan wall this near
  double huber = 0.05;  ///< world metres: residuals beyond this are down-weighted
  int iterations = 6;   ///< rounds of matching and refitting
  std::size_t min_points = 40;  ///< matched points of each kind the fit needs
  /// World metres: an outer faces' offset outside [-max_offset / 4, max_offset] is not trusted
  /// (walls are not thicker than twice this), nor a partition offset beyond half of it.
  double max_offset = 0.4;
  double max_scale_change = 0.03;  ///< share: a refined scale farther off is not trusted
  /// World metres: the outer walls' faces must lie at least this much farther off their strokes
  /// than the partitions' for the fit to be used. Offsets alike on both kinds do not move the
  /// scale (they are symmetric about every room), and growing every stroke by them cost a plan
  /// drawn from its own gridmap: the semi-real csail plan found 0.050 and 0.049 m, and its best
  /// model went from 0.011 to 0.025 m.
  double min_offset_difference = 0.03;
  /// The run localizes on the plan with its strokes grown to the faces (plan_at_faces): its
  /// filters, scan matches and pairs then meet the walls where the laser does.
  bool localize_on_faces = true;
};

/// Which of a plan's drawn walls have the building's outside behind them.
class ExteriorWalls {
 public:
  /// The outside of `plan`: the cells that are not walls, reached from the raster's edge once
  /// gaps in the walls narrower than twice `seal_radius` (plan metres) are closed, grown back up
  /// to the walls.
  ExteriorWalls(const OccupancyGrid& plan, double seal_radius);

  /// Whether the wall whose surface point is `surface` (plan metres), with `normal` pointing
  /// off the wall, has the outside behind it within `max_depth` plan metres.
  bool exterior(const Eigen::Vector2d& surface, const Eigen::Vector2d& normal,
                double max_depth) const;
  /// Whether cell (ix, iy) of the plan is outside the building.
  bool outside(int ix, int iy) const {
    return outside_[static_cast<std::size_t>(iy) * plan_.width() + static_cast<std::size_t>(ix)] !=
           0;
  }

 private:
  const OccupancyGrid& plan_;
  std::vector<char> outside_;  // per cell, row-major from the bottom row
};

/// A gridmap wall point matched to a plan wall surface.
struct FaceObservation {
  Eigen::Vector2d grid_point = Eigen::Vector2d::Zero();  ///< world metres
  Eigen::Vector2d surface = Eigen::Vector2d::Zero();     ///< the plan wall surface point
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();      ///< unit, off the wall, plan frame
  bool exterior = false;                                 ///< the outside lies behind the wall
};

/// What the refinement found. Offsets are plan metres off the drawn surface into the room.
struct WallFaceFit {
  bool fitted = false;               ///< trusted and used
  MapSimilarity similarity;          ///< the refined registration (the start's when not fitted)
  double exterior_offset = 0.0;      ///< plan metres: outer walls' faces off their strokes
  double partition_offset = 0.0;     ///< plan metres: the other walls'
  std::size_t exterior_points = 0;   ///< matched points on outer walls (last round)
  std::size_t partition_points = 0;  ///< and on the others
  std::string note;                  ///< what was found or why it was not used
};

/// Matches the gridmap's wall points to the plan's walls under a similarity, within a radius in
/// plan metres.
using FaceMatcher =
    std::function<std::vector<FaceObservation>(const MapSimilarity& similarity, double radius)>;

/// The registration `start` refined, point to plane, with the faces' two offsets as unknowns:
/// n . (s R g + t - surface) = offset(kind), robustly (Huber), re-matching each round.
WallFaceFit fit_wall_faces(const FaceMatcher& match, const MapSimilarity& start,
                           const WallFaceOptions& options);

/// `plan` with its strokes grown into the rooms up to the faces the fit found (the outer walls'
/// by its exterior offset, the others' by its partition offset; never shrunk), so that a robot
/// localizing on it meets walls where the laser does. `plan` itself when the fit was not used.
/// `max_depth`: plan metres, as ExteriorWalls::exterior.
OccupancyGrid plan_at_faces(const OccupancyGrid& plan, const ExteriorWalls& exterior,
                            const WallFaceFit& fit, double max_depth);

/// The offset (plan metres) a matched point's target lies off its drawn surface.
inline double face_offset(const WallFaceFit& fit, bool exterior) {
  if (!fit.fitted)
    return 0.0;
  return exterior ? fit.exterior_offset : fit.partition_offset;
}

}  // namespace floorgrid
