#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/evaluation/domain.hpp"
#include "floorgrid/evaluation/model_comparison.hpp"
#include "floorgrid/evaluation/model_evaluation.hpp"
#include "floorgrid/mapping/pair_noise.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/pipeline/map_alignment.hpp"
#include "floorgrid/pipeline/pair_sources.hpp"
#include "floorgrid/pipeline/plan_match.hpp"
#include "floorgrid/pipeline/wall_slide.hpp"

namespace floorgrid {

/// What the main job works on: a dataset already read (see io::load_dataset).
struct AlignmentInputs {
  const OccupancyGrid& plan_grid;             ///< the plan as a grid (plan metres)
  const VectorFloorplan* plan = nullptr;      ///< a DXF plan's walls (layers filtered), or null
  const Eigen::Matrix2Xd& plan_wall_samples;  ///< plan wall points every ~5 cm (plan metres)
  const OccupancyGrid& gridmap;               ///< the robot's map
  const RobotLog& log;                        ///< the run
  std::optional<StartPoses> start;            ///< the manifest's initial poses
  std::optional<double> plan_scale;           ///< the manifest's scale (nullopt: auto)
  GroundTruth truth_warp;  ///< a simulator's exact truth (plan -> grid), or empty
  const ReferencePairs* manual_pairs = nullptr;  ///< hand-picked truth pairs, or null
};

/// Where the reference pairs come from.
enum class PairSource {
  run,   ///< dual Monte Carlo localization of the robot's run
  maps,  ///< the gridmap aligned to the plan from the two maps alone (align_maps)
  both,  ///< the run's pairs and the maps' together
};

/// The name options and outputs spell: "run", "maps" or "both".
const char* to_string(PairSource source);
/// The source `name` spells; throws InputError naming `field` for another name.
PairSource parse_pair_source(const std::string& name, const std::string& field = "--pairs-from");

/// Every setting of the main job.
struct AlignmentOptions {
  DualLocalizerOptions localization;  ///< how pairs are made
  ModelComparisonOptions models;      ///< which models, cross-validation, back-and-forth
  /// The pairs slid along their gridmap walls before any model is fitted (0 rounds: not).
  WallSlideOptions wall_slide;
  /// Where the pairs come from (a dataset without a log: the maps, whatever this says).
  PairSource pairs_from = PairSource::run;
  /// How the maps are aligned (first, always: they seed and check the run, and their pairs
  /// stand in when the run's fail).
  MapAlignmentOptions maps_only;
  /// How the run's pairs are judged against the maps' alignment, and which are used.
  PairSourceOptions sources;
  /// Metres: wall distances are also summarized over the plan wall points this close to a
  /// pair (where the models have data).
  double near_pairs = 2.0;
  /// Metres: the gridmap's distance field for wall distances is capped here.
  double wall_distance_cap = 5.0;
  /// Metres between the plan wall samples of the evaluation domain (SPEC: every 5 cm).
  double domain_spacing = 0.05;
};

/// How far a model puts the plan's walls from the gridmap's walls (no truth needed): each plan
/// wall point mapped to the grid, its distance to the nearest occupied gridmap cell.
struct WallDistance {
  std::size_t points = 0;         ///< wall points mapped
  double median_m = 0.0;          ///< median distance over them
  std::size_t near_points = 0;    ///< of which within near_pairs of a pair
  double near_median_m = 0.0;     ///< median distance over those
  std::vector<double> distances;  ///< per wall point (plan_wall_samples order), metres
};

/// One model's judgement.
struct ModelAlignment {
  ModelReport report;          ///< fit, errors against the truth, back-and-forth
  WallDistance wall_distance;  ///< against the gridmap's walls
};

/// Progress of the main job.
struct AlignmentProgress {
  std::string stage;   ///< "localize", "fit", "evaluate"
  std::string detail;  ///< the phase or model
  std::size_t done = 0;
  std::size_t total = 0;
};

/// A bias every pair shares, which no cross-validation over them sees (PairSourceOptions::
/// shared_bias): the root sum of squares of its parts, world metres.
struct SharedBias {
  double std_m = 0.0;  ///< what every model's std_m carries
  /// What measured the first part: "agreement" (the run's pairs against the maps' alignment,
  /// PairSourceCheck::disagreement_local_median_m), "maps" (the maps' pairs are used: their bent
  /// map's scale spread over the pairs' radius of gyration), "option" (the options'
  /// align.models.mapping.uncertainty.shared_std was larger than the whole) or "none".
  std::string from = "none";
  double sources_m = 0.0;  ///< that part
  /// The second: the outer walls' faces off the drawn strokes (WallFaceFit::exterior_offset,
  /// world metres) when neither the maps' registration nor the run's scale refit took them
  /// out. Both sources then meet the laser's faces on the strokes and share the error: the
  /// building's outline drawn that much wider than the laser sees it.
  double faces_m = 0.0;
};

/// What the main job found.
struct Alignment {
  /// How pairs were made. Its `pairs` are the ones every model is fitted on: slid along their
  /// walls when options.wall_slide asks (the filters' own are then in `localized_pairs`).
  DualLocalization localization;
  /// The pairs as the filters made them, before the wall slide (empty when none slid).
  ReferencePairs localized_pairs;
  PairSource pairs_from = PairSource::run;  ///< where the pairs came from
  /// The maps' alignment (made first, whatever the source; its `pairs` are in
  /// localization.pairs when the pairs came from it, or appended to the run's there).
  std::optional<MapAlignment> maps;
  /// With a run: its pairs judged on their own and against the maps', and which were used.
  std::optional<PairSourceCheck> sources;
  /// What the wall slide did (its `pairs` left empty: they are localization.pairs).
  std::optional<WallSlide> wall_slide;
  double wall_slide_seconds = 0.0;  ///< of the wall slide
  /// The filters' pairs against the truth, before the wall slide (with a truth and a slide).
  std::optional<ErrorStatistics> localized_pair_errors;
  std::optional<ErrorStatistics> pair_errors;  ///< pairs against the truth (with a truth)
  PlanMatch plan_match;                        ///< whether the plan is of this building at all
  EvaluationDomain domain;                     ///< where models are judged
  std::vector<ModelAlignment> models;          ///< in the order fitted
  std::string chosen;                          ///< the model `auto` chose ("" without auto)
  double fit_seconds = 0.0;                    ///< all fits and cross-validations
  double evaluate_seconds = 0.0;               ///< all judging
  /// The process's peak resident memory (MiB) at the end of each stage that ran:
  /// maps_alignment, localize (with the pairs), wall_slide, fit (the fits and their judging).
  std::map<std::string, double> peak_memory_mib;
  /// The pairs' own noise from revisits (pair_noise), taken out of every model's std_m.
  std::optional<PairNoise> pair_noise;
  /// The bias every pair shares that every model's std_m carries (PairSourceOptions::
  /// shared_bias).
  SharedBias shared_bias;
  /// The truth as a function (plan -> grid), when the dataset has one.
  std::optional<GroundTruth> truth;
};

/// Called as the main job advances (may be empty).
using AlignmentProgressCallback = std::function<void(const AlignmentProgress&)>;

/// The main job (SPEC `align`): reference pairs by dual Monte Carlo localization, every model
/// fitted to them and judged against the truth over its domain (a simulator's warp: wall
/// points where the gridmap saw something; manual pairs through the dt model: wall points
/// inside their hull), and against the gridmap's walls. A model that cannot be fitted is
/// reported, not fatal. A localization that fails is reported in
/// `localization.status`, a plan that does not match the gridmap under the pairs (another
/// building's) in `plan_match`: no models are fitted then, none would be right. InputError for
/// bad input (see localize_dual).
Alignment align(const AlignmentInputs& inputs, const AlignmentOptions& options = {},
                const AlignmentProgressCallback& progress = {});

/// Each pair's distance from where the truth puts its plan point (`align` and `pairs` report it).
ErrorStatistics pair_errors(const ReferencePairs& pairs, const GroundTruth& truth);

/// A dataset's truth and the name of its domain: a simulator's warp ("warp"), or the
/// hand-picked pairs through the Delaunay model ("manual_pairs_hull", the thesis's ground
/// truth); kind "none" and no function without either. The one truth of `align` and `evaluate`.
struct DatasetTruth {
  std::optional<GroundTruth> plan_to_grid;  ///< plan -> grid, when there is a truth
  std::string kind = "none";                ///< "warp", "manual_pairs_hull" or "none"
};

/// The truth of `inputs` (its warp, else its manual pairs through dt).
DatasetTruth dataset_truth(const AlignmentInputs& inputs);

/// The truth's domain: plan wall samples every `spacing` metres where a warp is known to hold
/// (the gridmap saw something near), or inside the manual pairs' hull, with the plan scale the
/// truth gives there; no points without a truth.
EvaluationDomain truth_domain(const AlignmentInputs& inputs, const DatasetTruth& truth,
                              double spacing);

/// The distance from each plan wall point, mapped by `plan_to_grid`, to the nearest occupied
/// cell of `gridmap` (capped at `cap` metres), summarized over all points and over those
/// within `near` metres of a pair's plan point.
WallDistance wall_distance(const Eigen::Matrix2Xd& plan_wall_samples,
                           const Eigen::Matrix2Xd& mapped, const OccupancyGrid& gridmap,
                           const Eigen::Matrix2Xd& pair_points_in_plan, double near, double cap);

}  // namespace floorgrid
