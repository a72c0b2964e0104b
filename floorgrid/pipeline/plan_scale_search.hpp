#pragma once

#include "floorgrid/pipeline/plan_location.hpp"

namespace floorgrid {

/// Step 3 of localize_dual, when the plan's scale is not given: the plan filter tracks
/// ScaleSearchOptions::scans scans from the plan's start with a scale on each particle (a
/// random walk), and the scale it settles on is then profiled: the scale that puts the most
/// endpoints of its converged scans exactly on the plan's walls. Updates location.scale (and,
/// with a given start, location.registration) and the scale fields of `result`.
void search_plan_scale(const DualMaps& maps, const RobotLog& log,
                       const DualLocalizerOptions& options, PlanLocation& location,
                       DualLocalization& result);

/// Step 3 with the maps aligned first and no clear registration: up to
/// ScaleSearchOptions::maps_scans of the gridmap filter's sure scans are dead-reckoned on the
/// plan at each candidate scale around `prior` (world metres per plan metre; the range from
/// `prior_relative_std`), starting where `warp` (the maps' bent map) puts the first: each
/// predicted by the gridmap filter's motion over the scale and matched onto the plan's walls.
/// A building's scale shows along its corridors, where the scans alone cannot tell it: a
/// wrong scale carries the robot past the door frames and corners it should meet. The scale
/// that meets the most (refined between the lattice's steps) is kept through the run. No
/// particle is drawn: the same maps and gridmap poses give the same scale. Sets location and
/// the scale fields of `result`.
void search_plan_scale_from_maps(const DualMaps& maps, const RobotLog& log,
                                 const DualLocalizerOptions& options, const MapWarp& warp,
                                 double prior, double prior_relative_std, PlanLocation& location,
                                 DualLocalization& result);

}  // namespace floorgrid
