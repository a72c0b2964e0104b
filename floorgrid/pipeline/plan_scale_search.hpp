#pragma once

#include <cstddef>
#include <vector>

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

/// The scale at the top of a hump of counts over ascending `scales`: the vertex of a parabola
/// fitted (least squares) to the scales counting at least `share` of the way from the fewest
/// to the most, when it opens downwards and its vertex lies among them; else the scale
/// counting the most. std::invalid_argument without scales or with counts of another size.
double hump_top(const std::vector<double>& scales, const std::vector<std::size_t>& counts,
                double share);

/// Step 3 with the maps aligned first and no clear registration: up to
/// ScaleSearchOptions::maps_scans of the gridmap filter's sure scans are dead-reckoned on the
/// plan at each candidate scale around `prior` (world metres per plan metre; the range from
/// `prior_relative_std`), in segments that each start where `warp` (the maps' bent map) puts
/// their first scan: each scan predicted by the gridmap filter's motion over the scale and
/// matched onto the plan's walls. A building's scale shows along its corridors, where the
/// scans alone cannot tell it: a wrong scale carries the robot past the door frames and
/// corners it should meet. The top of the walls met over the scales (a parabola's vertex) is
/// kept through the run. No particle is drawn. Sets location and the scale fields of
/// `result`.
void search_plan_scale_from_maps(const DualMaps& maps, const RobotLog& log,
                                 const DualLocalizerOptions& options, const MapWarp& warp,
                                 double prior, double prior_relative_std, PlanLocation& location,
                                 DualLocalization& result);

}  // namespace floorgrid
