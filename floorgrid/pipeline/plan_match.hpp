#pragma once

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_registration.hpp"

namespace floorgrid {

/// Whether the plan is a drawing of the gridmap's building at all, judged after the pairs: the
/// similarity the pairs give (plan to grid, least squares), refined on the two maps as the
/// direct registration refines, and scored as it scores (the gridmap's walls on the plan's minus
/// the plan's walls in space the gridmap saw free). Filters can converge on a plan of another
/// building and make pairs that agree with themselves; the two whole maps then disagree.
struct PlanMatch {
  bool judged = false;     ///< false: the pairs do not determine a similarity, or no walls
  ScoredSimilarity score;  ///< the refined similarity (grid to plan) and its score
};

/// Judges the plan against the gridmap under `pairs` (plan metres -> grid metres).
PlanMatch judge_plan_match(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                           PlanWalls plan_walls, const ReferencePairs& pairs,
                           const MapRegistrationOptions& options = {});

/// Whether a judged match lets the run go on: its score at least `min_score` and at most
/// `max_in_free_space` of the plan's walls in the robot's free space (a match not judged is
/// let through: there was nothing to judge it on).
bool plan_match_accepted(const PlanMatch& match, double min_score, double max_in_free_space);

}  // namespace floorgrid
