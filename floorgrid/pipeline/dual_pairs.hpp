#pragma once

#include "floorgrid/pipeline/dual_maps.hpp"
#include "floorgrid/pipeline/plan_location.hpp"

namespace floorgrid {

/// Whether a scan gives pairs: both filters converged and consistent with each other and,
/// when poses are refined, both scan matches accepted.
bool usable_for_pairs(const ScanRecord& record, bool refine);

/// What refit_plan_scale gave.
struct ScaleRefit {
  double scale = 1.0;  ///< world metres per plan metre
  /// Where a surface shift was fitted with it and used: the same scans' scale fitted without
  /// it, on the drawn walls (DualLocalization::plan_scale_at_drawn_walls); 0 otherwise.
  double scale_at_drawn_walls = 0.0;
  bool shift_used() const { return scale_at_drawn_walls > 0.0; }
};

/// Refits the plan's scale jointly with the refined plan poses of every usable scan
/// (fit_scale; with `fit_shift`, and a shift of the walls' surfaces, used where it is at least
/// `min_shift` world metres) and stores the refitted poses in the records; returns the scale
/// (`scale` when fewer than options.min_scans scans are usable, or when the scale is
/// `registered` by the maps and the shift not used, unless ScaleRefitOptions::
/// raise_registered_scale applies: a registration not `at_faces` and a higher refit) and sets
/// result.plan_scale_std and result.plan_surface_shift.
ScaleRefit refit_plan_scale(DualLocalization& result, const RobotLog& log,
                            const WallField& plan_walls, const FilterRunnerOptions& plan_runner,
                            const ScaleRefitOptions& options, double scale, bool fit_shift,
                            double min_shift, bool registered, bool at_faces = false,
                            const GridRayCaster* plan_caster = nullptr);

/// Steps 4 and 5 of localize_dual: the plan filter tracks (track_plan) and, with an unknown
/// scale, the scale is refitted with the refined plan poses; when the refit moved it by more
/// than ScaleRefitOptions::retrack_change, the plan filter tracks again at the new scale.
/// Sets result.plan_scale and result.plan_scale_at_drawn_walls. `vector_plan`: the plan is a
/// vector drawing, whose lines place the walls exactly (ScaleRefitOptions::min_shift_pixels).
void track_plan_and_refit_scale(const DualMaps& maps, const RobotLog& log,
                                const DualLocalizerOptions& options, PlanLocation& location,
                                DualLocalization& result, const DualProgressCallback& progress,
                                bool vector_plan);

/// The pairs of every scan (result.pairs, result.rejections, ScanRecord::pairs) at the plan
/// scale result.plan_scale: from the refined poses when `refine`, else the filters' means.
/// First the plan poses' pull along the robot's heading is measured (result.pose_pull,
/// measure_pose_pull); when it is measured well, the plan poses are moved back by it.
void make_pairs(DualLocalization& result, const RobotLog& log, const WallField& plan_walls,
                const WallField& grid_walls, const PairExtractionOptions& options,
                const PosePullOptions& pull_options, bool refine);

/// Drops the pairs of scans that disagree with the other scans' (reject_outlier_scans):
/// updates result.pairs, the records' pair counts and the `outlier_scan` rejections.
void drop_outlier_scans(DualLocalization& result, const OutlierScanOptions& options);

/// result.converged_fraction and result.converged_periods from the records.
void summarize_convergence(DualLocalization& result);

}  // namespace floorgrid
