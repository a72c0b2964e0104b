#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_alignment.hpp"
#include "floorgrid/pipeline/plan_match.hpp"

namespace floorgrid {

/// How `align` weighs the run's pairs against the maps' alignment (SPEC revision 3: the maps are
/// registered first, the two sources are checked against each other, and the run's pairs are
/// used only when they vouch for the building).
struct PairSourceOptions {
  /// World metres: a gridmap wall point this near a pair's grid point is covered by the pairs.
  double coverage_radius = 2.0;
  /// The run's pairs must cover at least this share of the gridmap's walls...
  double min_coverage = 0.2;
  /// ... and come from at least this many scans, or this share of the log's scans when that is
  /// fewer (a handful of scans agree with themselves wherever they are: they cannot vouch for a
  /// building).
  std::size_t min_pair_scans = 20;
  double min_pair_scan_share = 0.25;
  /// ... and both filters must have been converged on at least this share of the scans (from
  /// the first where both were): a run that localized on the gridmap for a third of its scans
  /// (a gridmap whose resolution was given wrong) makes pairs only where it happened to fit.
  double min_converged_share = 0.5;
  /// The run's pairs agree with the maps' bent map when the median distance (world metres)
  /// between a pair's plan point and where the bent map puts its grid point is within their
  /// stated uncertainty: disagreement_sigmas times the root sum of squares of the pairs' noise
  /// (pair_noise) and the bent map's scale spread times the pairs' radius of gyration (a
  /// drawing wrong in places is placed by the maps as far off as its local scales differ), at
  /// least min_disagreement_tolerance. A wrong place or scale is off by metres.
  double disagreement_sigmas = 3.0;
  double min_disagreement_tolerance = 0.5;
  /// ... and their scales differ by at most this many of the maps' scale spread (at least
  /// min_scale_tolerance of the scale), plus how far the walls' faces moved the run's scale
  /// (RunPairsSummary::scale_at_drawn_walls).
  double scale_sigmas = 3.0;
  double min_scale_tolerance = 0.02;
  /// When they disagree, the run's pairs are kept only when the plan-match check scores them
  /// higher than the maps' by more than this. A tie goes to the maps: their alignment fits every
  /// wall at once, where a plan filter can slide along a corridor and still match the plan as
  /// well under one similarity (a real drawing's world on fr079, seed 2: the run's pairs 0.97 m
  /// off, plan match 0.6027 against the maps' 0.6025). Scores are in [-1, 1], and so is the
  /// margin: a negative one keeps the run's pairs when they score up to that much below.
  double run_match_margin = 0.02;
  /// World metres: when the run's pairs are used and agree with the maps', the maps' pairs
  /// farther than this from every run pair are added: they place the walls the robot never
  /// came near (rooms it did not enter, a drawing's corner it saw only from afar), where the
  /// models would otherwise extrapolate; near the run's they would only dilute them (0: none).
  double fill_radius = 2.0;
  /// Every model's std_m carries a bias the pairs share, which no cross-validation over them
  /// can see (ErrorModelOptions::shared_std; the larger of it and this): with the run's pairs
  /// and the maps' alignment agreeing, how far apart they lie (disagreement_local_median_m);
  /// with the maps' pairs alone, the bent map's scale spread over the pairs' radius of gyration
  /// (what the maps state of their own placement); and the outer walls' faces off the drawn
  /// strokes when neither source took them out (align's SharedBias). On the drawings of
  /// bench/real_matrix.sh, seeds 1-6, the chosen model's bands held the truth errors (2-sigma
  /// >= 85%, 1-sigma >= 55%) on 17 of 54 rows without it and 40 with it (README: "What std_m
  /// includes").
  bool shared_bias = true;
  /// World metres: the run's pairs' distances to the maps' alignment are averaged, as vectors,
  /// over square cells this wide (gridmap frame) before their median is the shared bias: a
  /// pair's own noise, which the models average out, leaves the mean; what every pair of a
  /// place shares stays (PairSourceCheck::disagreement_local_median_m).
  double bias_cell = 2.0;
};

/// Checks `options`; throws InputError naming `<prefix><field>`.
void validate(const PairSourceOptions& options, const std::string& prefix = "align.sources.");

/// The run's pairs checked on their own and against the maps' alignment.
struct PairSourceCheck {
  // The run.
  bool run_localized = false;  ///< the run made pairs (its localization succeeded)
  std::string run_failure;     ///< why the run's pairs are not used ("" when they are usable)
  PlanMatch run_match;         ///< the plan match under the run's pairs
  double coverage = 0.0;       ///< share of the gridmap's wall points the run's pairs cover
  std::size_t pair_scans = 0;  ///< scans that made pairs
  std::size_t scans = 0;       ///< scans in the log
  bool run_accepted = false;   ///< localized, plan match accepted, covering enough
  // The maps.
  bool maps_accepted = false;  ///< the maps' alignment was accepted (MapAlignment::accepted)
  PlanMatch maps_match;        ///< the plan match under the maps' pairs (when judged)
  /// Why the maps' pairs did not stand in for a failed run although the maps were accepted
  /// (their plan match failed the check), "" otherwise.
  std::string maps_failure;
  // The two against each other (when both were accepted).
  bool compared = false;
  double disagreement_median_m = 0.0;  ///< world metres, over the run's pairs
  double disagreement_p90_m = 0.0;     ///< world metres
  /// World metres: the median over the run's pairs of the mean disagreement vector of the pairs
  /// in their cell (PairSourceOptions::bias_cell): what the pairs of a place share.
  double disagreement_local_median_m = 0.0;
  double disagreement_tolerance_m = 0.0;  ///< how far the median may be, world metres
  double run_scale = 0.0;                 ///< the run's plan scale (world metres per plan metre)
  /// The run's scale fitted on the drawn walls (RunPairsSummary::scale_at_drawn_walls; 0 when
  /// the faces' offset was not fitted): how far they moved it widens scale_tolerance.
  double run_scale_at_drawn_walls = 0.0;
  double maps_scale = 0.0;       ///< the bent map's
  double scale_tolerance = 0.0;  ///< how far apart the two may be
  bool agree = false;
  /// The source whose pairs are used: run, maps, or none (neither passed: the job fails).
  std::string chosen = "none";
  /// The maps' pairs added where the run's pairs do not reach (PairSourceOptions::fill_radius),
  /// when the run's were chosen and agree with them.
  ReferencePairs fill;
  /// Why the run's pairs were not used, when the maps' were ("" otherwise).
  std::string fallback;
};

/// The root mean square distance of `points` from their mean (0 without points).
double radius_of_gyration(const Eigen::Matrix2Xd& points);

/// The share of the gridmap's occupied cells within `radius` metres of a point of
/// `points_in_grid`.
double wall_coverage(const OccupancyGrid& gridmap, const Eigen::Matrix2Xd& points_in_grid,
                     double radius);

/// Everything the check needs of the run.
struct RunPairsSummary {
  bool localized = false;                 ///< the localization succeeded
  std::string failure;                    ///< its message when not
  const ReferencePairs* pairs = nullptr;  ///< the run's pairs (plan -> grid)
  double plan_scale = 1.0;                ///< world metres per plan metre the pairs were made with
  double noise_m = 0.0;                   ///< the pairs' own noise (pair_noise), rms, world metres
  std::size_t pair_scans = 0;             ///< scans that made pairs
  std::size_t scans = 0;                  ///< scans in the log
  double converged_fraction = 1.0;        ///< DualLocalization::converged_fraction
  /// The run's scale fitted on the drawn walls, without the faces' offset
  /// (DualLocalization::plan_scale_at_drawn_walls), when its pairs' scale was refitted with
  /// the walls' faces off them; 0 otherwise. The maps' registration meets the gridmap's walls
  /// on the drawn ones, so the faces bias its scale too: by up to as much as they moved the
  /// run's (on HIH's thin strokes the maps' scale came out 2.3-2.7% low, the run's 1.2% low
  /// without the offset and 0.1% with it; on the house DXF the maps' 1.1% low, the run's 4.7%
  /// without it).
  double scale_at_drawn_walls = 0.0;
  PlanMatch match;              ///< the plan match under the pairs
  bool match_accepted = false;  ///< it passed the plan-match check
};

/// The pairs of `maps` (grid points) farther than `radius` from every point of `points_in_grid`.
ReferencePairs pairs_beyond(const ReferencePairs& maps, const Eigen::Matrix2Xd& points_in_grid,
                            double radius);

/// Judges the run's pairs (plan match, convergence, scans, coverage of the gridmap's walls),
/// compares them with the maps' alignment when both pass (their distance through the bent map,
/// their scales), and chooses: the run's pairs when they pass and agree with the maps (or the
/// maps did not pass); when they disagree, the run's only when the plan-match check (`judge`,
/// giving `maps_match`) scores them higher than the maps' by more than run_match_margin; the
/// maps' pairs when only the maps pass. The maps' pairs stand in only when their plan match
/// passes `accepts` too (null: any), the same check the run's passed or failed.
PairSourceCheck check_pair_sources(const RunPairsSummary& run, const MapAlignment* maps,
                                   const OccupancyGrid& gridmap, const PairSourceOptions& options,
                                   const std::function<PlanMatch(const ReferencePairs&)>& judge,
                                   const std::function<bool(const PlanMatch&)>& accepts = {});

}  // namespace floorgrid
