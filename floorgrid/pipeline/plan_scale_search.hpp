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

}  // namespace floorgrid
