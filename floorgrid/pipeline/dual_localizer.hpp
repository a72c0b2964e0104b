#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "floorgrid/localization/pair_extraction.hpp"
#include "floorgrid/localization/particle_filter.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/maps/visible_walls.hpp"
#include "floorgrid/pipeline/filter_runner.hpp"
#include "floorgrid/pipeline/outlier_scans.hpp"
#include "floorgrid/pipeline/plan_registration.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// The robot's start in both maps.
struct StartPoses {
  Pose2 plan;  ///< plan frame (plan metres)
  Pose2 grid;  ///< grid frame
};

/// The observation model a filter uses.
enum class ObservationModelKind {
  likelihood_field,  ///< distance-transform likelihood field (default)
  beam,              ///< thesis eq. 3.43-3.47 with ray casting
};

/// The plan filter's defaults: no augmented-MCL injection while tracking (a plan explains only
/// the walls, so its fit dips whenever furniture hides them, which is not divergence; and in
/// a corridor injected particles fit as well as the true ones), divergence only after ten
/// scans that explain almost nothing, and a lower fit to count as converged.
ParticleFilterOptions default_plan_filter_options();
/// The gridmap filter's defaults: no augmented-MCL injection while tracking either (along a
/// corridor it scatters a converged cloud and reads as divergence), and a higher fit to count
/// as converged (the gridmap holds what the laser sees).
ParticleFilterOptions default_grid_filter_options();

/// Every setting of the dual localization (defaults in one place).
struct DualLocalizerOptions {
  ParticleFilterOptions plan_filter = default_plan_filter_options();  ///< on the floorplan
  ParticleFilterOptions grid_filter = default_grid_filter_options();  ///< on the gridmap
  /// Each filter's observation model. The likelihood field by default for both: it tolerates
  /// what a plan lacks (furniture endpoints fall to its floor) and costs one lookup per beam;
  /// the beam model (thesis eq. 3.43-3.47) costs a ray cast per beam.
  ObservationModelKind plan_model = ObservationModelKind::likelihood_field;
  ObservationModelKind grid_model = ObservationModelKind::likelihood_field;  ///< the gridmap's
  /// The plan filter's likelihood field: wider than the gridmap's, since a plan is drawn, not
  /// measured (misdrawn walls, doors shown closed).
  LikelihoodFieldOptions plan_likelihood{0.15, 0.8, 0.2, 2.0, 0.5, true};
  LikelihoodFieldOptions grid_likelihood{0.1, 0.9, 0.1, 2.0, 0.5, true};  ///< the gridmap's
  /// Beam models (when chosen): a sharp hit, a fifth of the beams allowed to stop short on
  /// furniture, tempered by half.
  BeamModelOptions beam{0.7, 0.2, 0.1, 0.0, 0.05, 0.5, 0.0, 0.1, 0.5, false};
  ObservationOptions plan_observation{60};  ///< beams per scan of the plan filter
  ObservationOptions grid_observation{60};  ///< beams per scan of the gridmap filter
  /// How each filter is fed: update gate, improved proposal, scan matching (the plan's and the
  /// gridmap's).
  FilterRunnerOptions plan_runner, grid_runner;
  WallFieldOptions walls;  ///< the scan matchers' wall lookup
  /// Localize on the plan's walls as a robot inside sees them: the far faces of walls drawn as
  /// two lines (the outline's outer line, a wall's hollow) are dropped (visible_walls).
  bool visible_walls_only = true;
  VisibleWallsOptions visible;  ///< how the visible walls are found
  /// Match scans onto the plan by their beams that reach the plan's first wall along them
  /// (FilterRunnerOptions::beam_tolerance): the endpoints on furniture a plan lacks would pull
  /// the match towards the walls behind.
  bool plan_beam_consistency = true;
  PairExtractionOptions pairs;  ///< how endpoints become pairs
  /// Scans whose pairs disagree with the other scans' at the same walls are dropped.
  OutlierScanOptions outlier_scans;
  /// Pairs only from scans whose scan match succeeded on both maps (the refined poses), and
  /// never from a scan whose match is degenerate in either (a corridor, an aisle).
  bool refine_poses = true;

  // ---- the plan's start and scale ----
  /// Without a start: the run's laser endpoints, seen from the gridmap filter's poses, are
  /// gathered into a submap and located on the plan (register_on_plan).
  SubmapOptions submap;
  PlanRegistrationOptions registration;  ///< the submap's global search
  /// The plan's likelihood field for the registration: wide, since a whole run meets every
  /// misdrawn wall.
  LikelihoodFieldOptions registration_likelihood{0.25, 0.8, 0.2, 2.0, 1.0, true};
  /// Scales (world metres per plan metre) searched when the plan's scale is not given.
  ScaleRange scale_range{0.8, 1.25};
  /// The plan filter's model during the scale search. The likelihood field by default: on a
  /// plan drawn wrong the beam model punishes every reading that passes a misdrawn wall and
  /// drifts to whatever scale hides them; the likelihood field's bias (it stretches a scan to
  /// pull furniture endpoints onto the walls behind them) is removed by the profile that
  /// follows, which counts only endpoints exactly on walls.
  ObservationModelKind scale_search_model = ObservationModelKind::likelihood_field;
  ObservationOptions scale_search_observation{30};  ///< beams per scan of the scale search
  /// Random walk of the scale during the search, per square root of a metre travelled.
  double scale_walk = 0.01;
  int scale_search_scans = 300;  ///< scans of the scale search after the plan filter converged
  /// Then the scale is profiled (profile_scale) over the search's result times 1 +- this, in
  /// scale_profile_steps steps each way, on up to scale_profile_scans of its scans.
  double scale_profile_range = 0.1;
  int scale_profile_steps = 20;
  std::size_t scale_profile_scans = 60;
  /// With an unknown plan scale: refit it, with the refined plan poses of every scan used for
  /// pairs, by a joint Gauss-Newton (fit_scale), and make the pairs with that scale.
  bool refit_scale = true;
  /// When the refit moves the scale by more than this share, the plan filter tracks again with
  /// the refitted scale (and the scale is refitted on that), at most max_plan_passes passes.
  double retrack_scale_change = 0.002;
  int max_plan_passes = 2;
  int max_global_scans =
      600;  ///< a gridmap filter not converged by then: global localization failed

  // ---- the dual check: the two filters must agree through the plan's registration ----
  /// The local registration (LocalRegistration) from the last scans where both filters were
  /// sure: its window, the pairs it needs, and how many scans it stays valid without news.
  std::size_t local_window = 50;
  std::size_t local_min_pairs = 10;
  std::size_t local_max_age = 150;
  /// Plan metres and radians: a plan pose farther than this from where the local registration
  /// puts the gridmap filter's pose disagrees, and its scan makes no pairs. Allows for a plan
  /// drawn wrong by up to a metre, not for a filter turned the wrong way in a cluttered room.
  double local_distance = 1.0;
  double local_heading = 0.12;  ///< radians
  /// The plan filter is re-initialized when it disagrees by more than this (plan metres and
  /// radians) for consistency_scans scans: against the local registration when it is fresh...
  double local_reinitialize_distance = 2.0;
  double local_reinitialize_heading = 0.3;  ///< radians
  /// ... and otherwise against the global one (the start poses or the submap's registration,
  /// one similarity for the whole plan), which also judges the pairs then.
  double consistency_distance = 3.0;
  double consistency_heading = 0.5;  ///< radians
  /// Consecutive disagreeing scans (the gridmap filter converged) after which the plan filter
  /// is re-initialized around the registered gridmap pose.
  int consistency_scans = 10;
  /// Scans a plan filter may stay unconverged (the gridmap filter converged) before it is
  /// re-initialized there as well.
  int reconverge_scans = 40;
  double reinitialize_sigma = 1.0;          ///< plan metres: the new cloud's position spread
  double reinitialize_heading_sigma = 0.2;  ///< radians: its heading spread

  int threads = 2;         ///< threads of the observation models
  std::uint64_t seed = 1;  ///< randomness of both filters
};

/// Per scan: where each filter stood.
struct ScanRecord {
  std::size_t scan = 0;   ///< index into the log's scans
  FilterRecord plan;      ///< the plan filter (plan metres)
  FilterRecord grid;      ///< the gridmap filter
  std::size_t pairs = 0;  ///< pairs made from this scan
  /// The plan filter was re-initialized on this scan by the dual check.
  bool plan_reinitialized = false;
  /// The plan pose agrees with the gridmap pose through the registration (only judged while
  /// the gridmap filter is converged).
  bool consistent = true;
};

/// How often a filter diverged, and why (DivergenceReason names, and `inconsistent` for the
/// plan filter disagreeing with the gridmap filter).
struct DivergenceCount {
  std::size_t total = 0;                         ///< divergences
  std::map<std::string, std::size_t> by_reason;  ///< reason -> count
};

/// What the dual localization found.
struct DualLocalization {
  ReferencePairs pairs;           ///< plan metres -> grid metres
  PairRejections rejections;      ///< endpoints that did not become pairs, by reason
  std::vector<ScanRecord> scans;  ///< one per scan of the log
  /// Share of the scans, from the first scan where both filters were converged on, with both
  /// converged.
  double converged_fraction = 0.0;
  /// Scan index ranges [first, last] where both filters were converged.
  std::vector<std::pair<std::size_t, std::size_t>> converged_periods;
  /// The longest run of scans between two converged periods (how long re-converging took at
  /// worst), 0 with fewer than two periods.
  std::size_t longest_gap = 0;
  double plan_scale = 1.0;             ///< world metres per plan metre used for the pairs
  double plan_scale_std = 0.0;         ///< its uncertainty (0 when given)
  bool plan_scale_estimated = false;   ///< whether it was searched
  double plan_scale_search = 0.0;      ///< the particle filter's search result
  double plan_scale_search_std = 0.0;  ///< and its spread
  StartPoses start;                    ///< where each filter started (found or given)
  std::size_t grid_start_scan = 0;     ///< the scan the gridmap filter first converged on
  std::size_t plan_start_scan = 0;     ///< the scan the plan filter started tracking from
  /// Where the run lies on the plan (the gridmap filter's poses -> plan poses).
  std::optional<PlanRegistrationResult> registration;
  DivergenceCount plan_divergences;  ///< the plan filter's, while localizing
  DivergenceCount grid_divergences;  ///< the gridmap filter's
  std::size_t plan_corrections = 0;  ///< improved-proposal corrections of the plan filter
  std::size_t grid_corrections = 0;  ///< the same for the gridmap filter
  /// Particle-beam evaluations of the tracking passes' measurement updates (both filters).
  std::size_t tracking_evaluations = 0;
  double global_localization_seconds = 0.0;  ///< wall clock
  double scale_search_seconds = 0.0;         ///< wall clock (search and refit)
  double localize_seconds = 0.0;             ///< wall clock of the tracking passes
  double grid_seconds = 0.0;       ///< of which the gridmap filter's pass (global included)
  double pairs_seconds = 0.0;      ///< of pair extraction
  std::vector<std::string> notes;  ///< what happened, in words
};

/// Progress of a long run.
struct DualProgress {
  std::string phase;       ///< "gridmap", "plan: registration", "plan: scale search", "plan"
  std::size_t scan = 0;    ///< scans done in this phase
  std::size_t scans = 0;   ///< scans in this phase
  bool converged = false;  ///< the phase's filter at the last scan
  std::size_t pairs = 0;   ///< usable scans so far (plan phase)
};

/// Dual Monte Carlo localization (thesis 4.6): one particle filter on the gridmap and one on
/// the rasterized floorplan, fed the same odometry and scans; pairs from the laser endpoints of
/// every scan where both are converged (and, by default, where both scans match their map).
///
/// 1. The gridmap filter localizes globally from its best hypotheses for the first scan (or
///    tracks from the given start) and runs through the log.
/// 2. The plan is related to the run: from the given start poses, or, without them, by
///    locating on the plan the submap of the laser endpoints seen from the gridmap filter's
///    converged poses (global localization with a whole tour's worth of evidence). Without a
///    plan scale, the plan filter then searches it: its particles carry scales with a random
///    walk for scale_search_scans.
/// 3. The plan filter tracks from where the registration puts the gridmap filter's pose, with
///    the scale found. The dual check re-initializes it around that pose when the two disagree
///    or it stays lost while the gridmap filter is converged.
/// 4. With an unknown scale, the scale is refitted jointly with the refined plan poses.
/// 5. Pairs: each kept endpoint from the plan pose (ranges divided by the scale) and from the
///    gridmap pose, where it lies on a wall of both maps.
///
/// `plan_geometry`, when given (a DXF plan's walls, in the plan grid's frame), is what scans
/// are matched onto in the plan instead of the plan grid's occupied cells: exact walls, not
/// cells. InputError when the gridmap filter never converges or the run has no endpoints.
DualLocalization localize_dual(const OccupancyGrid& plan, const OccupancyGrid& grid,
                               const RobotLog& log, const std::optional<StartPoses>& start,
                               const std::optional<double>& plan_scale,
                               const DualLocalizerOptions& options = {},
                               const std::function<void(const DualProgress&)>& progress = {},
                               const VectorFloorplan* plan_geometry = nullptr);

}  // namespace floorgrid
