#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "floorgrid/localization/pair_extraction.hpp"
#include "floorgrid/localization/particle_filter.hpp"
#include "floorgrid/localization/robot_log.hpp"
#include "floorgrid/localization/scan_matcher.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/localization/wall_field.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// The robot's start in both maps.
struct StartPoses {
  Pose2 plan;  ///< plan frame (plan metres)
  Pose2 grid;  ///< grid frame
};

/// The observation model both filters use.
enum class ObservationModelKind {
  likelihood_field,  ///< distance-transform likelihood field (default)
  beam,              ///< thesis eq. 3.43-3.47 with ray casting
};

/// The plan filter's defaults: fewer particles (its beam model costs a ray cast per beam), no
/// augmented-MCL injection while tracking (a plan explains only the walls, so its fit dips
/// whenever furniture hides them, which is not divergence), and divergence only after ten
/// scans that explain almost nothing.
ParticleFilterOptions default_plan_filter_options();

/// Every setting of the dual localization (defaults in one place).
struct DualLocalizerOptions {
  ParticleFilterOptions plan_filter = default_plan_filter_options();  ///< on the floorplan
  ParticleFilterOptions grid_filter;  ///< the filter on the gridmap
  /// The plan filter's model. The beam model by default: a plan lacks the furniture the laser
  /// sees, and only the beam model tells a reading stopped short by it (explained) from one
  /// reaching past a wall (not explained); the likelihood field, blind to that, pulls
  /// furniture endpoints onto the walls behind them and biases pose and scale.
  ObservationModelKind plan_model = ObservationModelKind::beam;
  /// The gridmap filter's model: the gridmap holds the furniture, so the fast likelihood field.
  ObservationModelKind grid_model = ObservationModelKind::likelihood_field;
  /// The plan filter's likelihood field: wider than the gridmap's, since a plan is drawn, not
  /// measured (misdrawn walls, doors shown closed).
  LikelihoodFieldOptions plan_likelihood{0.15, 0.8, 0.2, 2.0, 0.5, true};
  LikelihoodFieldOptions grid_likelihood{0.1, 0.9, 0.1, 2.0, 0.5, true};       ///< the gridmap's
  /// Beam models: a sharp hit (5 cm: the plan's walls are exact lines), a fifth of the beams
  /// allowed to stop short on furniture, tempered by half.
  BeamModelOptions beam{0.7, 0.2, 0.1, 0.0, 0.05, 0.5, 0.0, 0.1, 0.5, false};
  ObservationOptions plan_observation{30};  ///< beams per scan of the plan filter
  ObservationOptions grid_observation{60};  ///< beams per scan of the gridmap filter
  PairExtractionOptions pairs;     ///< how endpoints become pairs
  /// Refine both filters' mean poses by matching the scan onto each map's walls before making
  /// pairs (a particle cloud's mean is only as sharp as the cloud; the match is sharper), and
  /// drop the scans whose match fails or cannot pin the pose down (a corridor, an aisle).
  bool refine_poses = true;
  WallFieldOptions walls;                     ///< the matchers' wall lookup
  ScanMatchOptions plan_match;                ///< scan matching on the plan
  ScanMatchOptions grid_match;                ///< scan matching on the gridmap
  ObservationOptions match_observation{180};  ///< beams per scan of the matching
  /// With an unknown plan scale: refit it, with the refined plan poses of every scan used for
  /// pairs, by a joint Gauss-Newton (fit_scale), and make the pairs with that scale.
  bool refit_scale = true;
  /// Scales (world metres per plan metre) searched when the plan's scale is not given.
  ScaleRange scale_range{0.8, 1.25};
  /// Random walk of the scale during the search, per square root of a metre travelled.
  double scale_walk = 0.01;
  int scale_search_scans = 300;  ///< scans of the search after the plan filter converged
  int max_global_scans = 600;    ///< a filter not converged by then: global localization failed
  /// Metres and radians of odometry before the filters are updated again: updating a standing
  /// robot with the same scan over and over makes the filters overconfident.
  double update_min_translation = 0.05;
  double update_min_rotation = 0.05;  ///< radians
  int threads = 2;                    ///< threads of the observation models
  std::uint64_t seed = 1;             ///< randomness of both filters
};

/// Per scan: where each filter stood.
struct ScanRecord {
  std::size_t scan = 0;                                 ///< index into the log's scans
  FilterState plan_state = FilterState::uninitialized;  ///< after this scan
  FilterState grid_state = FilterState::uninitialized;  ///< after this scan
  bool plan_converged = false;                          ///< plan filter converged
  bool grid_converged = false;                          ///< grid filter converged
  Pose2 plan_pose;        ///< the plan filter's mean pose (plan metres)
  Pose2 grid_pose;        ///< the grid filter's mean pose
  std::size_t pairs = 0;  ///< pairs made from this scan
  /// The refined poses (when refine_poses): the matches of this scan on each map.
  ScanMatch plan_match, grid_match;
  /// Each filter's last convergence test (of the last scan it was updated with).
  ConvergenceCheck plan_check, grid_check;
  double plan_fit = 0.0;  ///< the plan filter's mean beam likelihood at its last update
  double grid_fit = 0.0;  ///< the grid filter's
};

/// What the dual localization found.
struct DualLocalization {
  ReferencePairs pairs;           ///< plan metres -> grid metres
  PairRejections rejections;      ///< endpoints that did not become pairs, by reason
  std::vector<ScanRecord> scans;  ///< one per scan of the localizing pass
  /// Share of the scans, from the first scan where both filters were converged on, with both
  /// converged.
  double converged_fraction = 0.0;
  /// Scan index ranges [first, last] where both filters were converged.
  std::vector<std::pair<std::size_t, std::size_t>> converged_periods;
  double plan_scale = 1.0;                   ///< world metres per plan metre used for the pairs
  double plan_scale_std = 0.0;               ///< its uncertainty (0 when given)
  bool plan_scale_estimated = false;         ///< whether it was searched
  double plan_scale_search = 0.0;            ///< the particle filter's search result
  double plan_scale_search_std = 0.0;        ///< and its spread
  std::optional<StartPoses> start;           ///< the start found by global localization (or given)
  std::size_t global_scans_plan = 0;         ///< scans the plan filter needed to converge globally
  std::size_t global_scans_grid = 0;         ///< the same for the grid filter
  std::size_t plan_divergences = 0;          ///< times the plan filter diverged while localizing
  std::size_t grid_divergences = 0;          ///< the same for the grid filter
  double global_localization_seconds = 0.0;  ///< wall clock
  double scale_search_seconds = 0.0;         ///< wall clock
  double localize_seconds = 0.0;             ///< wall clock of the localizing pass
  double pairs_seconds = 0.0;                ///< of which spent extracting pairs
  std::vector<std::string> notes;            ///< what happened, in words
};

/// Progress of a long run.
struct DualProgress {
  std::string phase;            ///< "global localization", "scale search", "localize"
  std::size_t scan = 0;         ///< scans done in this phase
  std::size_t scans = 0;        ///< scans in this phase (an upper bound for the first two)
  bool plan_converged = false;  ///< at the last scan
  bool grid_converged = false;  ///< at the last scan
  std::size_t pairs = 0;        ///< pairs so far
};

/// Dual Monte Carlo localization (thesis 4.6): one particle filter on the rasterized floorplan
/// and one on the gridmap, fed the same odometry and scans; pairs from the laser endpoints of
/// every scan where both are converged.
///
/// Without a start, each filter localizes globally from its best hypotheses for the first scan
/// and runs until it converges; the pose it then has is carried back to the first scan by the
/// odometry and the localizing pass tracks from there. Without a plan scale, the plan filter
/// also searches the scale: its particles carry scales over `scale_range` with a random walk,
/// for `scale_search_scans` after converging; the mean and spread of the estimates over the
/// second half of that window give the scale and its uncertainty, and the localizing pass
/// uses that scale. InputError when a filter never converges globally.
///
/// `plan_geometry`, when given (a DXF plan's walls, in the plan grid's frame), is what scans
/// are matched onto in the plan instead of the plan grid's occupied cells: exact walls, not
/// cells.
DualLocalization localize_dual(const OccupancyGrid& plan, const OccupancyGrid& grid,
                               const RobotLog& log, const std::optional<StartPoses>& start,
                               const std::optional<double>& plan_scale,
                               const DualLocalizerOptions& options = {},
                               const std::function<void(const DualProgress&)>& progress = {},
                               const VectorFloorplan* plan_geometry = nullptr);

}  // namespace floorgrid
