#pragma once

#include <optional>
#include <string>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/plan_unit_choice.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/pipeline/map_registration.hpp"

namespace floorgrid {

/// How the robot's map decides between the units a drawing may be in.
struct PlanUnitFitOptions {
  /// The scales tried under each unit: the expected floorplan_scale (1 when it is auto: a
  /// drawing is made at its true size) times or divided by this. Below 2.54 (in / cm), so that
  /// no two units share a scale.
  double scale_margin = 1.5;
  double min_score = 0.25;  ///< registration score a unit needs to be chosen by the run
  /// How much better than the drawing's choice another unit must fit to overrule it.
  double clear_margin = 0.15;
  /// A candidate's plan is rasterized at the job's resolution, coarser when it would need more
  /// cells than this (a unit that makes the building a kilometre wide).
  std::size_t max_cells = 16'000'000;
  /// Its min_scale and max_scale are set per unit; no last refinement on every wall point (the
  /// units need the score, not the scale to 0.1%).
  MapRegistrationOptions registration = [] {
    MapRegistrationOptions o;
    o.final_points = 0;
    return o;
  }();
};

/// Checks `options`; InputError naming `units.<field>` when one is out of range.
void validate(const PlanUnitFitOptions& options);

/// How well the gridmap fits the plan under one unit.
struct PlanUnitFit {
  PlanUnit unit = PlanUnit::m;   ///< the unit tried
  double probability = 0.0;      ///< what the drawing alone gives it
  bool tried = false;            ///< false: its plan could not be drawn (too large, no walls)
  double score = -1.0;           ///< the registration's best score near the expected scale
  double floorplan_scale = 0.0;  ///< world metres per plan metre (in this unit) it found
};

/// What the run says of the drawing's units.
struct PlanUnitDecision {
  std::vector<PlanUnitFit> fits;  ///< one per candidate, the drawing's order
  PlanUnit drawn = PlanUnit::m;   ///< the drawing's choice
  PlanUnit unit = PlanUnit::m;    ///< the unit to use: the drawing's, unless the run overrules it
  bool confirmed = false;         ///< whether the drawing's unit fits clearly best (or alone fits)
  std::string reason;             ///< one sentence

  /// Whether the run overruled the drawing's choice.
  bool overruled() const { return unit != drawn; }
};

/// Registers the gridmap on the plan under each candidate unit (`plan` is in metres under
/// `drawn_unit`), over scales near `expected_scale` only, and keeps the drawing's unit unless
/// another one fits clearly better and well. `raster` says how the job draws the plan.
/// InputError on bad options (validate).
PlanUnitDecision fit_plan_units(const OccupancyGrid& gridmap, const VectorFloorplan& plan,
                                PlanUnit drawn_unit,
                                const std::vector<PlanUnitCandidate>& candidates,
                                std::optional<double> expected_scale,
                                const RasterizeOptions& raster,
                                const PlanUnitFitOptions& options = {});

}  // namespace floorgrid
