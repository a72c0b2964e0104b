#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_correlation.hpp"
#include "floorgrid/pipeline/map_fit_score.hpp"

namespace floorgrid {

/// How the gridmap is registered on the plan directly, before any filter runs.
struct MapRegistrationOptions {
  /// Plan metres per world metre searched: [1 / max_scale, 1 / min_scale] of SPEC's
  /// floorplan_scale, so 0.25-4 covers a plan scanned or exported at any resolution.
  double min_scale = 0.25;
  double max_scale = 4.0;
  double scale_step = 0.015;      ///< relative step of the scale lattice of the profile search
  double profile_bin = 0.25;      ///< world metres per bin of the wall profiles
  int candidates = 12;            ///< profile candidates verified in 2D and refined
  std::size_t max_points = 3000;  ///< wall points of each map used in 2D, evenly thinned
  /// Wall points of each map in the best candidate's last refinement (0 or <= max_points: no
  /// such refinement). With 3000 points ACES's plan scale came out 0.06-0.15% too large, with
  /// every wall point 0.03-0.05%.
  std::size_t final_points = 40000;
  double sigma = 0.15;  ///< world metres: how near a wall a point must lie to count
  /// A plan wall that the transform puts more than this (world metres) inside the gridmap's
  /// observed free space is a wall the robot would have seen: it counts against the transform.
  double free_violation_distance = 0.4;
  /// When the wall profiles' best candidate scores below this in 2-D, candidates of a 2-D
  /// correlation search are refined and scored too (> 1: always, < -1: never). A partial or
  /// bent gridmap's profiles do not line up with the whole plan's: the maps-only alignment
  /// always searches (MapAlignmentOptions::correlation_below). A run's registration does not by
  /// default: on fr079's locally wrong drawing it found a similarity scoring 0.33 where the
  /// profiles' scored 0.29, and every model's error doubled (gp 0.46 -> 0.97 m).
  double correlation_below = -2.0;
  MapCorrelationOptions correlation;  ///< that search's lattice
  /// How many distinct other candidates MapRegistration::alternatives keeps.
  int alternatives = 4;
};

/// Checks `options`; throws InputError naming `<prefix><field>`.
void validate(const MapRegistrationOptions& options,
              const std::string& prefix = "align.localization.plan_location.map_registration.");

/// What register_maps found.
struct MapRegistration {
  bool found = false;     ///< a transform was scored (false: a map had no walls)
  ScoredSimilarity best;  ///< the best transform after refinement
  /// The refined candidates of another scale (beyond 5%) or pose (beyond 2 m or 10 degrees)
  /// than the best and than each other, best first, at most
  /// MapRegistrationOptions::alternatives: other places the gridmap could be, for an alignment
  /// that looks further than the similarity.
  std::vector<ScoredSimilarity> alternatives;
  /// The best of the alternatives (a zero score when there is none): how clearly the best won.
  ScoredSimilarity runner_up() const {
    return alternatives.empty() ? ScoredSimilarity{} : alternatives.front();
  }
  std::size_t candidates = 0;  ///< verified in 2D
  bool correlation = false;    ///< whether the 2-D correlation search ran
  double seconds = 0.0;        ///< wall clock
};

/// Registers the gridmap on the plan over scale, rotation and translation, coarse to fine:
/// both maps' walls are turned to their dominant direction; their wall profiles along both axes
/// are correlated over the scale lattice and every shift, for the four quarter turns (and 36
/// turns when a map has no dominant direction); the best candidates are scored in 2D (the
/// gridmap's walls near the plan's, minus the plan's walls in space the gridmap saw free) and
/// refined by a pattern search over scale, angle and translation; the best is refined once more
/// on up to `final_points` wall points. The gridmap's walls are matched
/// to the plan's wall surfaces as `plan_walls` says (a stroke's free-side edge, or a line).
MapRegistration register_maps(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                              PlanWalls plan_walls, const MapRegistrationOptions& options = {});

/// register_maps with the maps' scorer given (built with options.max_points and
/// free_violation_distance); it is left scoring on options.final_points wall points, those the
/// best transform was scored on last.
MapRegistration register_maps(MapFitScorer& scorer, const MapRegistrationOptions& options = {});

/// `start` refined on the two maps as register_maps refines its candidates, with its score.
ScoredSimilarity refine_map_similarity(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                                       PlanWalls plan_walls, const MapSimilarity& start,
                                       const MapRegistrationOptions& options = {});

}  // namespace floorgrid
