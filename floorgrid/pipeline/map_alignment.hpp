#pragma once

#include <string>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_registration.hpp"

namespace floorgrid {

/// How the gridmap is aligned to the plan from the two maps alone (no robot run).
struct MapAlignmentOptions {
  /// World metres between the displacement lattice's nodes in the first stage; each later
  /// stage halves it down to last_spacing.
  double first_spacing = 8.0;
  double last_spacing = 2.0;  ///< world metres, the finest lattice
  /// World metres: a gridmap wall point is matched to a plan wall this near (first stage); the
  /// radius shrinks geometrically to last_radius in the finest stage.
  double first_radius = 1.0;
  double last_radius = 0.3;      ///< world metres
  int rounds = 3;                ///< correspondence rounds per stage
  double stiffness = 1.0;        ///< the lattice's membrane weight (DisplacementLattice::fit)
  double point_spacing = 0.2;    ///< world metres between the gridmap wall points used
  double max_normal_angle = 30;  ///< degrees between matched walls' directions, at most
  /// World metres: the final correspondences this near their plan wall become the pairs.
  double pair_radius = 0.15;
  /// The alignment is accepted when its fitness (MapFit::score of the bent map) is at least
  /// this. On the 32 Halmstad sensor maps the right alignments measured 0.24-0.69; sensor maps
  /// on another building's layout (and fr079's map on E5's, E5's on fr079's drawing) -0.13 to
  /// 0.17, and 0.35 for a small map (HIH_01) inside a large building (E5), which this does not
  /// catch.
  double min_fitness = 0.2;
  /// The registration's correlation_below here (> 1: its 2-D correlation search always runs:
  /// the wall profiles' 1-D search registered 12 of the 27 Halmstad sensor maps, with it all 27).
  double correlation_below = 2.0;
};

/// Checks `options`; throws InputError naming `<prefix><field>`.
void validate(const MapAlignmentOptions& options, const std::string& prefix = "align.maps_only.");

/// What align_maps found.
struct MapAlignment {
  MapRegistration registration;  ///< the global similarity it started from
  /// Plan wall surface points and the gridmap wall points matched to them (metres), one per
  /// gridmap wall point within pair_radius of the refined plan walls.
  ReferencePairs pairs;
  /// The bent gridmap's fit (MapFitScorer, on the registration's final wall points): its score
  /// is the fitness.
  MapFit fit;
  bool accepted = false;           ///< fit.score >= min_fitness
  std::string diagnosis;           ///< why not accepted (empty when accepted)
  std::size_t points = 0;          ///< gridmap wall points used
  int stages = 0;                  ///< lattice stages run
  double median_distance_m = 0.0;  ///< matched points' distance to the plan walls at the end
  double seconds = 0.0;            ///< wall clock
};

/// The gridmap aligned to the plan from the maps alone: a global registration over scale,
/// rotation and translation (register_maps), then a non-rigid refinement, coarse to fine: each
/// gridmap wall point, mapped by the similarity and a smooth displacement lattice, is matched
/// to the nearest plan wall surface within a shrinking radius (rejected when the walls'
/// directions disagree), and the lattice is refitted to move the points across their walls
/// onto them (point to plane: along a wall only its ends and corners tell). The final matches
/// are reference pairs for every mapping model. Scores the result as the registration does;
/// not accepted below options.min_fitness.
MapAlignment align_maps(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                        PlanWalls plan_walls, const MapRegistrationOptions& registration = {},
                        const MapAlignmentOptions& options = {});

}  // namespace floorgrid
