#pragma once

#include <optional>

#include "floorgrid/pipeline/gridmap_localization.hpp"

namespace floorgrid {

/// What step 2 found: where the run lies on the plan and how sure the plan filter may start.
struct PlanLocation {
  std::optional<StartPoses> given;   ///< the given start, when it held
  PlanRegistration registration;     ///< gridmap poses -> plan poses (one similarity)
  double scale = 1.0;                ///< world metres per plan metre (given, or found so far)
  double scale_sigma = 0.0;          ///< its spread for the scale search (0 when given)
  double start_sigma = 0.0;          ///< plan metres: the plan filter's first spread
  double start_heading_sigma = 0.0;  ///< radians
  /// The scale and the registration came from registering the gridmap on the plan directly,
  /// clearly enough that the plan filter's scale search is not needed.
  bool from_maps = false;
  /// And the scale is kept as the maps gave it, not refitted after tracking (a raster plan:
  /// the refit is biased by its strokes' thickness, the registration of a plan drawn where the
  /// laser saw the walls is not; see ScaleRefitOptions::raise_registered_scale for one that
  /// did not meet the outer walls' faces).
  bool keep_scale = false;
  /// And that registration met the outer walls' faces (the maps' faces fit was used,
  /// MapAlignment::faces): it is not biased low by them.
  bool scale_at_faces = false;
};

/// Step 2 of localize_dual: the plan is related to the run from the given start poses or,
/// without them, by locating on the plan the submap of the laser endpoints seen from the
/// gridmap filter's sure poses (register_on_plan; with an unknown scale, over the scale range).
/// Sets result.start, result.registration and result.plan_start_scan. InputError when the run
/// has no endpoints or the plan no free space.
PlanLocation locate_run_on_plan(const DualMaps& maps, const DualLocalizerInputs& inputs,
                                const GridmapLocalization& gridmap,
                                const DualLocalizerOptions& options, DualLocalization& result);

/// The similarity of the given start poses at `scale`: gridmap poses -> plan poses.
PlanRegistration registration_of(const StartPoses& start, double scale);

/// The plan filter's first cloud: around `pose` (plan metres and radians), with the scale fixed
/// or spread for a search.
TrackingStart plan_start(const Pose2& pose, double position_sigma, double heading_sigma,
                         double scale, double scale_sigma);

}  // namespace floorgrid
