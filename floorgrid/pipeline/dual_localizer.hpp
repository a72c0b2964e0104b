#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "floorgrid/localization/pair_extraction.hpp"
#include "floorgrid/localization/particle_filter.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/maps/visible_walls.hpp"
#include "floorgrid/pipeline/filter_runner.hpp"
#include "floorgrid/pipeline/map_alignment.hpp"
#include "floorgrid/pipeline/map_registration.hpp"
#include "floorgrid/pipeline/outlier_scans.hpp"
#include "floorgrid/pipeline/plan_registration.hpp"
#include "floorgrid/pipeline/pose_pull.hpp"
#include "floorgrid/pipeline/submap_check.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// The robot's start in both maps.
struct StartPoses {
  Pose2 plan;  ///< plan frame (plan metres)
  Pose2 grid;  ///< grid frame
};

/// What the dual localization works on. Everything referenced must outlive the call.
struct DualLocalizerInputs {
  const OccupancyGrid& plan;     ///< the plan as a grid (plan metres)
  const OccupancyGrid& gridmap;  ///< the robot's map (world metres)
  const RobotLog& log;           ///< the run: odometry and scans
  /// The start in both maps (the manifest's initial_pose); without it, global localization.
  std::optional<StartPoses> start = std::nullopt;
  /// World metres per plan metre when known; without it, the scale is searched.
  std::optional<double> plan_scale = std::nullopt;
  /// A DXF plan's walls in the plan grid's frame, or null: scans are then matched onto these
  /// exact walls instead of the plan grid's occupied cells.
  const VectorFloorplan* plan_geometry = nullptr;
  /// The two maps aligned before the run (align_maps), or null: its registration replaces the
  /// run's own, and when it was accepted its bent map seeds the run (see PlanLocationOptions).
  const MapAlignment* maps = nullptr;
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

/// How one map's particle filter localizes.
struct MapFilterOptions {
  ParticleFilterOptions filter;  ///< the particle filter
  /// Its observation model. The likelihood field by default: it tolerates what a plan lacks
  /// (furniture endpoints fall to its floor) and costs one lookup per beam; the beam model
  /// (thesis eq. 3.43-3.47) costs a ray cast per beam.
  ObservationModelKind model = ObservationModelKind::likelihood_field;
  LikelihoodFieldOptions likelihood;  ///< the likelihood field (always built: global seeding)
  ObservationOptions observation{.max_beams = 60};  ///< beams per scan of the filter
  /// How the filter is fed: update gate, improved proposal, scan matching.
  FilterRunnerOptions runner;
};

/// The plan filter's settings: its likelihood field is wider than the gridmap's, since a plan
/// is drawn, not measured (misdrawn walls, doors shown closed).
MapFilterOptions default_plan_options();
/// The gridmap filter's settings.
MapFilterOptions default_grid_options();

/// Step 1: the gridmap filter localizes globally (or tracks from the given start).
struct GridmapLocalizationOptions {
  /// A gridmap filter not converged after this many scans: global localization failed.
  int max_global_scans = 600;
  /// A gridmap filter that diverges after converging restarts first as a wide cloud around its
  /// last converged pose carried on by the odometry (the robot is most likely near there; a
  /// global restart from an ambiguous scan can wander a building of look-alike corridors for
  /// dozens of scans), and globally when that has not converged within this many scans (0:
  /// always globally at once).
  int restart_near_scans = 10;
  /// That cloud's spread, metres (growing by a tenth per metre travelled since) and radians.
  double restart_sigma = 0.5;
  double restart_heading_sigma = 0.25;
};

/// Step 2: where the run lies on the plan.
struct PlanLocationOptions {
  /// Localize on the plan's walls as a robot inside sees them: the far faces of walls drawn as
  /// two lines (the outline's outer line, a wall's hollow) are dropped (visible_walls).
  bool visible_walls_only = true;
  VisibleWallsOptions visible;  ///< how the visible walls are found
  /// Without a start: the run's laser endpoints, seen from the gridmap filter's poses, are
  /// gathered into a submap and located on the plan (register_on_plan).
  SubmapOptions submap;
  PlanRegistrationOptions registration;  ///< the submap's global search
  /// The plan's likelihood field for the registration: wide, since a whole run meets every
  /// misdrawn wall.
  LikelihoodFieldOptions registration_likelihood{.sigma_hit = 0.25,
                                                 .z_hit = 0.8,
                                                 .z_rand = 0.2,
                                                 .max_distance = 2.0,
                                                 .beam_weight = 1.0,
                                                 .unknown_is_free = true};
  /// Without a scale: the gridmap is first registered on the plan directly (register_maps,
  /// scale 0.25-4x, any rotation). When its score is at least map_min_score and its scale lies
  /// outside scale_search.range, the search covers its scale times 1 +- map_scale_margin
  /// instead (inside, the search runs over its usual range, which it resolves more finely).
  bool register_maps = true;
  MapRegistrationOptions map_registration;  ///< that registration
  double map_min_score = 0.25;              ///< score (on walls - in free space) it needs
  double map_scale_margin = 0.08;           ///< share: the scale range around its scale
  /// When its best beats the runner-up by this much, its scale and pose are used as they are
  /// (the plan filter starts there, no scale search; the scale is refitted on the pairs' scans).
  double map_clear_margin = 0.15;
  /// After the pairs: the similarity they give, refined on the two maps as the registration
  /// refines, must score at least this (gridmap walls on plan walls minus plan walls in free
  /// space, [-1, 1]) or the run fails: the plan is of another building or floor. Measured: the
  /// right plan 0.61-0.90 on 20 semi-real datasets (bends up to a metre) and 0.33 on fr079's
  /// drawing (wrong in places); other buildings' plans -0.54 to -0.27 from the pairs filters
  /// made on them; a warehouse's plan given the office's own pairs 0.08 (the refinement hides
  /// the plan where the robot saw nothing); a run whose pairs were 5 m off 0.10.
  double min_plan_match = 0.15;
  /// ... and no more than this share of the plan's walls (near the gridmap's known cells) may
  /// lie where the robot saw free space: the right plan 0.00-0.05 (fr079's drawing), a run
  /// whose pairs were 5 m off along Seattle's corridor 0.25 (scoring 0.23).
  double max_plan_walls_in_free_space = 0.15;
  /// With the maps aligned first and their alignment accepted (DualLocalizerInputs::maps), the
  /// run starts from it: the plan filter where the bent map puts the gridmap filter's pose,
  /// with these spreads (world metres and radians: a prior, not a constraint, so that a
  /// drawing wrong in places is still followed), the scale searched from the maps' scale with
  /// their spread (at least maps_min_scale_share of it), and the dual check's global
  /// registration the bent map rather than one similarity.
  bool start_from_maps = true;
  double maps_start_sigma = 0.5;
  double maps_start_heading_sigma = 0.15;  ///< radians
  double maps_min_scale_share = 0.01;
  /// Plan metres and radians: the plan filter's first spread around a given start pose...
  double given_start_sigma = 0.2;
  double given_start_heading_sigma = 0.1;  ///< radians
  /// ... and around the start the registration found (coarser: a lattice's steps).
  double registered_start_sigma = 1.0;
  double registered_start_heading_sigma = 0.2;  ///< radians
};

/// Step 3: the plan's scale, searched by the plan filter when it is not given.
struct ScaleSearchOptions {
  /// Scales (world metres per plan metre) searched when the plan's scale is not given.
  ScaleRange range{.min = 0.8, .max = 1.25};
  /// Share of the range: the scales' spread at the search's start when no registration found
  /// a scale first (a given start with an unknown scale).
  double initial_sigma_share = 0.25;
  /// The plan filter's model during the search. The likelihood field by default: on a plan
  /// drawn wrong the beam model punishes every reading that passes a misdrawn wall and drifts
  /// to whatever scale hides them; the likelihood field's bias (it stretches a scan to pull
  /// furniture endpoints onto the walls behind them) is removed by the profile that follows,
  /// which counts only endpoints exactly on walls.
  ObservationModelKind model = ObservationModelKind::likelihood_field;
  ObservationOptions observation{.max_beams = 30};  ///< beams per scan of the search
  /// With the maps aligned first (and no clear registration), no particle searches the
  /// scale: of every k-th scan of the log (up to maps_scans), those where the gridmap filter
  /// was sure are dead-reckoned on the plan (search_plan_scale_from_maps) at scales over the
  /// maps' scale times 1 +- (maps_sigmas times its spread, within
  /// maps_min_range..maps_max_range) in profile_steps steps each way; the top of the walls
  /// met over the scales is kept through the run. No particle is drawn.
  std::size_t maps_scans = 600;
  /// ... in segments of this many of them, each from where the maps put its first scan.
  std::size_t maps_segment_scans = 12;
  /// The scale is the vertex of a parabola through the scales whose count is at least this
  /// share of the way from the fewest to the most.
  double maps_fit_share = 0.3;
  double maps_sigmas = 3.0;
  double maps_min_range = 0.03;
  double maps_max_range = 0.15;
  /// Random walk of the scale during the search, per square root of a metre travelled.
  double walk = 0.01;
  int scans = 300;  ///< scans of the search after the plan filter started
  /// Then the scale is profiled (profile_scale) over the search's result times 1 +- this, in
  /// profile_steps steps each way, on up to profile_scans of its scans.
  double profile_range = 0.1;
  int profile_steps = 20;
  std::size_t profile_scans = 60;
};

/// Step 4: the dual check while the plan filter tracks: the two filters must agree through
/// the plan's registration.
struct DualCheckOptions {
  /// The local registration (LocalRegistration) from the last scans where both filters were
  /// sure: its window, the pairs it needs, and how many scans it stays valid without news.
  std::size_t local_window = 50;
  std::size_t local_min_pairs = 10;
  std::size_t local_max_age = 150;
  /// Metres (world: plan metres times the plan's scale) and radians: a plan pose farther than
  /// this from where the local registration puts the gridmap filter's pose disagrees, and its scan
  /// makes no pairs. The local registration (the last scans' similarity) already follows a plan
  /// drawn wrong by up to a metre over the building; half a metre more is a filter slipped along
  /// a corridor (ACES and Orebro: 0.5-0.8 m for 10-40 scans), or turned the wrong way in a
  /// cluttered room.
  double local_distance = 0.5;
  /// Metres per metre: local_distance grows by this with the distance from the gridmap pose to
  /// the nearest pose the local registration was fitted on (carried farther, a bend it does
  /// not know shows more).
  double local_distance_growth = 0.05;
  double local_heading = 0.12;  ///< radians
  /// The plan filter is re-initialized when it disagrees by more than this (world metres and
  /// radians) for consistency_scans scans: against the local registration when it is fresh...
  double local_reinitialize_distance = 2.0;
  double local_reinitialize_heading = 0.3;  ///< radians
  /// ... and otherwise against the global one (the start poses or the submap's registration,
  /// one similarity for the whole plan), which also judges the pairs then.
  double consistency_distance = 3.0;
  double consistency_heading = 0.5;  ///< radians
  /// Consecutive disagreeing scans (the gridmap filter converged; the plan filter converged or
  /// not) after which the plan filter is re-initialized around the registered gridmap pose.
  int consistency_scans = 10;
  /// A plan filter off by more than this many times the re-initialization distance (or
  /// heading) is re-initialized after gross_scans such scans instead: the patience above is for
  /// a filter hovering about the tolerance, not for one a room away (Orebro: 4-7 m off for 10
  /// scans after a 3 m jump between two scans). gross_scans 0: never.
  double gross_factor = 2.0;
  int gross_scans = 2;
  /// Scans a plan filter may stay unconverged (the gridmap filter converged) before it is
  /// re-initialized there as well.
  int reconverge_scans = 40;
  /// A plan filter that declares itself lost (diverged, recovering) while the gridmap filter
  /// is converged is re-initialized at once where the gridmap filter says, instead of
  /// searching the plan by itself (a plan's look-alike rooms and corridors lure it away).
  bool restart_when_lost = true;
  /// The other way round: a gridmap filter lost while the plan filter is sure gets a second
  /// gridmap filter started where the plan filter says (with the spreads below), whose records
  /// replace the lost ones while it is converged; it is given up after this many unconverged
  /// scans (0: never started). FHW: 6 scans with 30-48% of their readings under 0.8 m (people
  /// close around the robot) threw the gridmap filter off for about 35 while the plan filter
  /// stayed right.
  int mend_scans = 10;
  /// World metres and radians: the re-initialized cloud's spread around the pose the local
  /// registration gives...
  double local_reinitialize_sigma = 0.3;
  double local_reinitialize_heading_sigma = 0.1;  ///< radians
  /// ... and around the pose the global registration gives.
  double reinitialize_sigma = 1.0;
  double reinitialize_heading_sigma = 0.2;  ///< radians
  /// The plan filter's pose checked against the submap of the last scans (SubmapCheck); when
  /// it is re-placed, the scans since the last check make no pairs, and the local
  /// registration starts afresh. It re-places with the local spreads above.
  SubmapCheckOptions submap;
};

/// Whether the scale refit fits a surface shift (ScaleRefitOptions::surface_shift).
enum class SurfaceShift {
  automatic,  ///< fitted on every plan, used where at least min_shift
  always,     ///< fitted on every plan and used whatever its size
  never,      ///< the scale alone, as the refit did before
};

/// Step 5: with an unknown plan scale, the scale refitted with the refined plan poses.
struct ScaleRefitOptions {
  /// Refit the scale, with the refined plan poses of every scan used for pairs, by a joint
  /// Gauss-Newton (fit_scale), and make the pairs with that scale.
  bool enabled = true;
  /// Fit with the scale a shift of every plan wall's surface towards the laser that sees it
  /// (fit_scale's fit_shift; DualLocalization::plan_surface_shift). A vector plan's walls are
  /// lines, often single ones, where the laser meets faces half a wall's thickness in front:
  /// fitted with the scale alone they shrink every room, bias the scale low and pull the poses
  /// forward. A raster plan's scans meet its ink's edges (plan_wall_line), where its faces are
  /// when its strokes are drawn as thick as the walls; a wall drawn as a thin line has its faces
  /// in front of them (the Halmstad HIH layout's 1-pixel strokes: 0.054 m, and the scale 1.9-2%
  /// low without the shift).
  SurfaceShift surface_shift = SurfaceShift::automatic;
  /// Refit also a scale the maps' registration gave (PlanLocation::keep_scale) where the
  /// refit fits the surface shift (fitted with the scale alone, the walls' thickness biased
  /// the refit, which is why the registration's scale was kept).
  bool refit_registered_scale = true;
  /// Where the shift is not used, a scale the maps' registration gave is kept, unless that
  /// registration did not meet the outer walls' faces (their fit not used) and the scale
  /// refitted alone comes out higher: then the refit is used. The laser sees an outer wall
  /// drawn as a line at its inner face, so a registration of the gridmap's outline on the
  /// drawn one comes out low (on bench/real_matrix.sh's drawings, seeds 1-6, the maps' scale
  /// was low on all 50 rows that compared it, by 0.1-3.0%); a refit lower still is the walls'
  /// thickness biasing the refit too. On the 40 rows that kept the registered scale, a refit used
  /// whatever its direction moved the scale 0.75-1.46% further down on three; used only when
  /// higher, 11 rows moved towards the truth and none away.
  bool raise_registered_scale = true;
  /// World metres: the fitted shift is used only where it is at least this large; a plan whose
  /// walls' faces lie on its lines has its scale fitted alone, as before, and keeps a scale the
  /// registration gave.
  double min_shift = 0.01;
  /// On a raster plan the shift is used only where it is also at least this many of its
  /// pixels (world metres at the searched scale): within a pixel the ink's edges do not place
  /// the faces, and on a building of corridors the shift and the scale trade off. On
  /// fr079's real drawing (0.057 m pixels) the shift came out 0.022-0.029 m over seeds 1-3
  /// and moved the scale 3.9-4.7% up, away from its hand-made pairs' similarity and 0.7%
  /// apart; on the Halmstad HIH layout's 1-pixel strokes, 1.1-1.9 pixels (0.054-0.095 m).
  double min_shift_pixels = 1.0;
  std::size_t min_scans = 10;  ///< matched scans the refit needs, else the search's scale stays
  int max_iterations = 30;     ///< of the joint Gauss-Newton
  int jackknife_blocks = 20;   ///< blocks of scans for the scale's standard deviation
  /// A refit farther than this share from the searched scale is not trusted (too few or bad
  /// scans): the search's scale stays.
  double max_change = 0.1;
  /// When the refit moves the scale by more than this share, the plan filter tracks again with
  /// the refitted scale (and the scale is refitted on that), at most max_plan_passes passes.
  double retrack_change = 0.002;
  int max_plan_passes = 2;
  /// A pass tracked again is kept only when at least this share of the last pass's matched
  /// scans (those the refit used) matched again; else the last pass's poses and scale stay:
  /// house seed 3 of bench/real_matrix.sh's drawings, tracked again at a scale its first
  /// pass's shift moved, matched 23 scans where the first had 360, and their refit put the
  /// scale 8.9% off.
  double retrack_min_share = 0.5;
};

/// Where the scan matchers meet a raster plan's walls (DualLocalizerOptions::plan_wall_line).
enum class PlanWallLine {
  cell_centres,  ///< at its ink cells' centres
  ink_edges,     ///< at its ink's edges: half a plan cell off the centres, on the laser's side
  automatic,     ///< at the ink's edges where the maps' faces say so (ink_edge_min_offset)
};

/// Every setting of the dual localization (defaults in one place).
struct DualLocalizerOptions {
  MapFilterOptions plan = default_plan_options();  ///< the filter on the floorplan
  MapFilterOptions grid = default_grid_options();  ///< the filter on the gridmap
  /// The beam model of the filters that choose it: a sharp hit, a fifth of the beams allowed
  /// to stop short on furniture, tempered by half.
  BeamModelOptions beam{.weight_hit = 0.7,
                        .weight_unexpected = 0.2,
                        .weight_random = 0.1,
                        .weight_max = 0.0,
                        .sigma_hit = 0.05,
                        .lambda_unexpected = 0.5,
                        .max_range = 0.0,
                        .max_window = 0.1,
                        .beam_weight = 0.5,
                        .unknown_is_occupied = false};
  WallFieldOptions walls;  ///< the scan matchers' wall lookup
  /// Match scans onto the plan by their beams that reach the plan's first wall along them
  /// (FilterRunnerOptions::beam_tolerance): the endpoints on furniture a plan lacks would pull
  /// the match towards the walls behind.
  bool plan_beam_consistency = true;
  /// Where the scan matchers meet a raster plan's walls (WallField::surface_offset). At the
  /// ink's edges is right for a drawing whose walls are filled in as thick as built or thicker
  /// than drawn (an architect's drawing): the laser meets the ink's edge or lies in front of it,
  /// and matched onto the cells' centres a scan stops half a cell short of every wall ahead,
  /// pulling the plan's poses forward (a 180-degree laser sees no wall behind). At the cells'
  /// centres is right for a plan traced over a gridmap's occupied cells, whose ink reaches half
  /// a cell in front of the surfaces the laser met. A vector plan's walls are exact either way.
  PlanWallLine plan_wall_line = PlanWallLine::automatic;
  /// World metres: with PlanWallLine::automatic, the ink's edges are used when the maps' faces
  /// fit found the partitions' faces at least this far off their strokes. Set on the simulated
  /// architects' drawings (0.059-0.130 m, seeds 1-3) and the plans traced over gridmaps
  /// (0.026-0.049 m, seed 1); on fresh seeds the two overlap (0.047 m on a drawing, 0.056 m on
  /// a traced plan), so it decides what is likely, not what is certain.
  double ink_edge_min_offset = 0.055;
  /// Pairs only from scans whose scan match succeeded on both maps (the refined poses), and
  /// never from a scan whose match is degenerate in either (a corridor, an aisle).
  bool refine_poses = true;
  /// The plan filter moves by the gridmap filter's motion between scans where that one is
  /// converged (FilterRunner::guide), not by the odometry: on a sparse log the odometry's noise
  /// over a metre's step (several degrees) loses a plan filter whose scans see few drawn walls.
  bool guide_plan_by_gridmap = true;

  GridmapLocalizationOptions gridmap_localization;  ///< step 1
  PlanLocationOptions plan_location;                ///< step 2
  ScaleSearchOptions scale_search;                  ///< step 3
  DualCheckOptions dual_check;                      ///< step 4
  ScaleRefitOptions scale_refit;                    ///< step 5
  PairExtractionOptions pairs;                      ///< how endpoints become pairs
  /// The plan poses' pull along the robot's heading, measured from revisits and taken out.
  PosePullOptions pose_pull;
  /// Scans whose pairs disagree with the other scans' at the same walls are dropped.
  OutlierScanOptions outlier_scans;

  int threads = kDefaultThreads;  ///< threads of the observation models
  std::uint64_t seed = 1;         ///< randomness of both filters (see SeedStream)
};

/// Each filter draws from its own stream of the options' seed, so that a change in one step
/// does not shift the randomness of another: the stream's seed is seed + offset.
enum class SeedStream : std::uint64_t {
  gridmap_filter = 1,     ///< the gridmap filter
  scale_search = 2,       ///< the plan filter of the scale search
  plan_filter = 3,        ///< the tracking plan filter (each re-initialization takes the next)
  gridmap_reseed = 1000,  ///< a gridmap filter re-seeded at scan i takes this + i
  /// a gridmap filter started where the plan filter says at scan i takes this + i
  gridmap_mend = 1'000'000'000,
};

/// The seed of a stream.
std::uint64_t stream_seed(std::uint64_t seed, SeedStream stream, std::uint64_t index = 0);

/// Per scan: where each filter stood.
struct ScanRecord {
  std::size_t scan = 0;   ///< index into the log's scans
  FilterRecord plan;      ///< the plan filter (plan metres)
  FilterRecord grid;      ///< the gridmap filter
  std::size_t pairs = 0;  ///< pairs made from this scan
  /// The plan filter was re-initialized on this scan by the dual check.
  bool plan_reinitialized = false;
  /// `grid` is the record of a gridmap filter started where the plan filter said (the first
  /// one was lost here).
  bool grid_mended = false;
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

/// Whether the dual localization reached its end (numerical trouble is a result, not an
/// exception: the caller decides what a failure means).
struct LocalizationStatus {
  bool ok = true;  ///< both filters localized; pairs were made
  /// What failed, in words, with what to check (empty when ok).
  std::string message;
  /// The dataset field most likely at fault: "gridmap", "initial_pose", "log", ... (empty when
  /// ok).
  std::string field;
};

/// What the dual localization found.
struct DualLocalization {
  LocalizationStatus status;      ///< whether it succeeded
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
  double plan_scale = 1.0;      ///< world metres per plan metre used for the pairs
  double plan_scale_std = 0.0;  ///< its uncertainty (0 when given)
  /// World metres by which the plan walls' surfaces were found nearer the laser than the
  /// scan matchers met them, fitted with the scale (ScaleRefitOptions::surface_shift; 0 when
  /// not fitted; measured even where it was below min_shift and not used), and its standard
  /// deviation.
  double plan_surface_shift = 0.0;
  double plan_surface_shift_std = 0.0;
  /// Where the pairs' scale and poses were refitted with that shift (it was at least
  /// ScaleRefitOptions::min_shift), the scale refitted on the same scans without it; 0 when
  /// the shift was not used (metrics.json plan_surface_shift_used): how far the faces moved the
  /// scale, which bounds how far they may have moved the
  /// maps' registration's, which meets the gridmap's walls on the drawn lines or ink edges
  /// (RunPairsSummary::scale_at_drawn_walls).
  double plan_scale_at_drawn_walls = 0.0;
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
  /// How the gridmap filter restarted after diverging.
  struct GridRestarts {
    std::size_t near = 0;         ///< around its last converged pose
    std::size_t near_failed = 0;  ///< of those, not converged in time: restarted globally
    std::size_t global = 0;       ///< from a scan's best hypotheses over the whole map
    /// Lost while the plan filter was sure: started where the plan filter said...
    std::size_t from_plan = 0;
    std::size_t mended_scans =
        0;  ///< ... and the scans it was converged on while the first was not
  } grid_restarts;
  std::size_t plan_corrections = 0;  ///< improved-proposal corrections of the plan filter
  std::size_t grid_corrections = 0;  ///< the same for the gridmap filter
  /// Plan filter steps that moved by the gridmap filter's motion (guide_plan_by_gridmap).
  std::size_t plan_guided_steps = 0;
  /// Particle-beam evaluations of the tracking passes' measurement updates (both filters).
  std::size_t tracking_evaluations = 0;
  double global_localization_seconds = 0.0;  ///< wall clock
  double scale_search_seconds = 0.0;         ///< wall clock (search and refit)
  double localize_seconds = 0.0;             ///< wall clock of the tracking passes
  double grid_seconds = 0.0;   ///< of which the gridmap filter's pass (global included)
  double pairs_seconds = 0.0;  ///< of pair extraction
  /// The plan poses' pull along the robot's heading (measure_pose_pull; nullopt when not
  /// measured or no place was revisited facing another way).
  std::optional<PosePull> pose_pull;
  std::vector<std::string> notes;  ///< what happened, in words
};

/// Progress of a long run.
struct DualProgress {
  std::string phase;       ///< "gridmap", "plan"
  std::size_t scan = 0;    ///< scans done in this phase
  std::size_t scans = 0;   ///< scans in this phase
  bool converged = false;  ///< the phase's filter at the last scan
  std::size_t pairs = 0;   ///< usable scans so far (plan phase)
};

/// Called every few scans of a long run (may be empty).
using DualProgressCallback = std::function<void(const DualProgress&)>;

/// Dual Monte Carlo localization (thesis 4.6): one particle filter on the gridmap and one on
/// the rasterized floorplan, fed the same odometry and scans; pairs from the laser endpoints of
/// every scan where both are converged (and, by default, where both scans match their map).
///
/// 1. Localize on the gridmap: the gridmap filter localizes globally from its best hypotheses
///    for the first scan (or tracks from the given start) and runs through the log.
/// 2. Locate the run on the plan: from the given start poses, or, without them, by locating on
///    the plan the submap of the laser endpoints seen from the gridmap filter's converged poses
///    (global localization with a whole tour's worth of evidence).
/// 3. Search the plan scale (when not given): the plan filter's particles carry scales with a
///    random walk; the result is then profiled on the scans' endpoints.
/// 4. Track the plan: the plan filter tracks from where the registration puts the gridmap
///    filter's pose, with the scale found. The dual check re-initializes it around that pose
///    when the two disagree or it stays lost while the gridmap filter is converged.
/// 5. Refit the scale (when not given) jointly with the refined plan poses, tracking again
///    when it moved; then the pairs: each kept endpoint from the plan pose (ranges divided by
///    the scale) and from the gridmap pose, where it lies on a wall of both maps.
///
/// InputError for bad input (fewer than two scans, a scale that is not a positive number, a run
/// without endpoints, a plan without free space); a gridmap filter that never converges is
/// reported in `status`.
DualLocalization localize_dual(const DualLocalizerInputs& inputs,
                               const DualLocalizerOptions& options = {},
                               const DualProgressCallback& progress = {});

}  // namespace floorgrid
