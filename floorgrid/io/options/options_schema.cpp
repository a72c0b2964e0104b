#include "floorgrid/io/options/options_schema.hpp"

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/linear_combination.hpp"

namespace floorgrid {

// Generated from the structs' /// comments, then edited: each field's name is the struct's, its
// unit and one line of what it does, and the values an options file may give it (refused at
// read with the file, line and option; the library's own checks run later, without a line);
// defaults are never repeated here. Upper bounds keep what an option makes the job allocate or
// loop over finite and sane (particles, lattices, dense matrices), far above any useful value.
namespace {

constexpr OptionRange kPositive = above(0.0);                    // > 0, finite
constexpr OptionRange kNonNegative = at_least(0.0);              // >= 0, finite
constexpr OptionRange kShare = between(0.0, 1.0);                // [0, 1]
constexpr OptionRange kPositiveShare = above_to(0.0, 1.0);       // (0, 1]
constexpr OptionRange kOpenShare = {.min = 0.0, .max = 1.0};     // (0, 1)
constexpr OptionRange kScore = between(-1.0, 1.0);               // a registration's score
constexpr OptionRange kDistance = between(0.0, kMaxCoordinate);  // metres
constexpr OptionRange kNoise = between(0.0, 100.0);              // odometry noise alpha
constexpr OptionRange kOneOrTwo = between(1.0, 2.0);             // threads of some steps
constexpr OptionRange kThreads = between(1.0, 256.0);            // threads
constexpr OptionRange kSeed = at_least(0.0);                     // any seed below 2^64
constexpr OptionRange kPairBudget = between(3.0, 1e7);           // pairs kept
constexpr OptionRange kDensePoints = between(3.0, 100000.0);     // N of an N x N matrix

}  // namespace

void visit(OptionVisitor& v, GpLatticeOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "",
           .doc = "Interpolate the mean from a lattice (false: the exact formula everywhere)",
           .choices = {}});
  v.field("tolerance", o.tolerance,
          {.unit = "m",
           .doc = "The largest acceptable |lattice - exact| of the mean",
           .choices = {},
           .range = kPositive});
  v.field("initial_spacing", o.initial_spacing,
          {.unit = "length scales",
           .doc = "First lattice spacing per axis",
           .choices = {},
           .range = kPositive});
  v.field("margin", o.margin,
          {.unit = "",
           .doc = "Length scales the lattice reaches beyond the training points",
           .choices = {},
           .range = kNonNegative});
  v.field("max_nodes", o.max_nodes,
          {.unit = "",
           .doc = "Give up (exact formula everywhere) rather than use more nodes (64 bytes each)",
           .choices = {},
           .range = between(4, 1e8)});
  v.field("max_attempts", o.max_attempts,
          {.unit = "",
           .doc = "Refinements at most before giving up",
           .choices = {},
           .range = between(1, 100)});
}

void visit(OptionVisitor& v, RpropOptions& o) {
  v.field("initial_step", o.initial_step,
          {.unit = "",
           .doc = "First step of every parameter, parameter units, > 0",
           .choices = {},
           .range = kPositive});
  v.field("increase", o.increase,
          {.unit = "",
           .doc = "eta+: step factor while the gradient keeps its sign (> 1)",
           .choices = {},
           .range = above(1.0)});
  v.field("decrease", o.decrease,
          {.unit = "",
           .doc = "eta-: step factor after a sign change, in (0, 1)",
           .choices = {},
           .range = kOpenShare});
  v.field("min_step", o.min_step,
          {.unit = "",
           .doc = "Smallest step, parameter units, > 0",
           .choices = {},
           .range = kPositive});
  v.field("max_step", o.max_step,
          {.unit = "",
           .doc = "Largest step, parameter units, >= min_step",
           .choices = {},
           .range = kPositive});
  v.field("max_iterations", o.max_iterations,
          {.unit = "",
           .doc = "Objective evaluations at most, >= 1",
           .choices = {},
           .range = between(1, 1e6)});
  v.field("tolerance", o.tolerance,
          {.unit = "",
           .doc = "Converged when the objective changes by less than this",
           .choices = {},
           .range = kNonNegative});
  v.require(o.max_step >= o.min_step, "max_step", ">= min_step");
  // lower and upper are not options: the tuning sets them from its own bounds.
}

void visit(OptionVisitor& v, ErrorModelOptions& o) {
  v.field("min_residuals", o.min_residuals,
          {.unit = "",
           .doc = "Held-out pairs needed at least (fewer: no std_m)",
           .choices = {},
           .range = at_least(3)});
  v.field("variance_scale", o.variance_scale,
          {.unit = "",
           .doc = "Factor on the variance fitted to the held-out errors when no runs folds "
                  "give the model's level",
           .choices = {},
           .range = above_to(0.0, 1e6)});
  v.field("min_level_fraction", o.min_level_fraction,
          {.unit = "",
           .doc = "The level's floor as a fraction of the runs folds' held-out RMS error",
           .choices = {},
           .range = kPositiveShare});
  v.field("local_radius", o.local_radius,
          {.unit = "m",
           .doc = "Held-out errors this near a point scale its std (0: no local part)",
           .choices = {},
           .range = between(0, 1e3)});
  v.field("local_prior", o.local_prior,
          {.unit = "",
           .doc = "Weight of the global fit against the nearby held-out errors",
           .choices = {},
           .range = above_to(0.0, 1e6)});
  v.field("shared_std", o.shared_std,
          {.unit = "m",
           .doc = "A bias all pairs share, added to every std_m in quadrature (align sets it "
                  "from its two pair sources' disagreement when larger)",
           .choices = {},
           .range = between(0, 1e3)});
}

void visit(OptionVisitor& v, CrossValidationOptions& o) {
  v.field("folds", o.folds,
          {.unit = "", .doc = "k of k-fold, >= 2", .choices = {}, .range = between(2, 1000)});
  v.field("max_pairs", o.max_pairs,
          {.unit = "",
           .doc = "Pairs binned down to this before the folds (cost bound)",
           .choices = {},
           .range = between(2, 1e8)});
  enum_field(v, "kind", o.kind,
             {{"blocked", CrossValidationKind::blocked},
              {"random", CrossValidationKind::random},
              {"runs", CrossValidationKind::runs}},
             "Folds of whole square blocks of the grid frame (the error away from the pairs), "
             "pairs dealt at random (near-copies stay in training), or stretches of the pairs in "
             "their order (a run's pairs: each stretch predicted from the other passes)");
  v.field("block_size", o.block_size,
          {.unit = "m",
           .doc = "Side of the blocks of blocked folds (0: a few metres, chosen from the "
                  "pairs' extent and density)",
           .choices = {},
           .range = kDistance});
}

void visit(OptionVisitor& v, ThinPlateSplineLatticeOptions& o) {
  v.field("spacing", o.spacing,
          {.unit = "m",
           .doc = "Between lattice nodes, tried first (halved until the measured error is within "
                  "half the tolerance)",
           .choices = {},
           .range = kPositive});
  v.field("margin", o.margin,
          {.unit = "m",
           .doc = "Added around the box on every side",
           .choices = {},
           .range = kNonNegative});
  v.field("threads", o.threads,
          {.unit = "",
           .doc = "Threads building the nodes (1 or 2)",
           .choices = {},
           .range = kOneOrTwo});
  v.field("tolerance", o.tolerance,
          {.unit = "m",
           .doc = "Largest acceptable |lattice - exact spline|",
           .choices = {},
           .range = kPositive});
  v.field("max_nodes", o.max_nodes,
          {.unit = "",
           .doc = "Give up (the exact spline everywhere) rather than use more nodes (64 bytes "
                  "each)",
           .choices = {},
           .range = between(4, 1e8)});
}

void visit(OptionVisitor& v, GpPredictionOptions& o) {
  v.group("lattice", "The mean's lattice (fast, within lattice.tolerance metres)",
          [&] { visit(v, o.lattice); });
  v.field("threads", o.threads,
          {.unit = "",
           .doc = "Threads for batches and the lattice, 1 or 2",
           .choices = {},
           .range = kOneOrTwo});
}

void visit(OptionVisitor& v, GpTuningOptions& o) {
  v.field("max_points", o.max_points,
          {.unit = "",
           .doc = "Tune on at most this many points (a farthest-point subsample)",
           .choices = {},
           .range = kDensePoints});
  v.field(
      "min_noise_std", o.min_noise_std,
      {.unit = "m",
       .doc = "The smallest noise std allowed (sn^2 on K's diagonal bounds its condition number)",
       .choices = {},
       .range = kPositive});
  v.field(
      "min_length_scale_factor", o.min_length_scale_factor,
      {.unit = "",
       .doc = "Smallest length scale, in median nearest-neighbour distances of the tuning points",
       .choices = {},
       .range = kPositive});
  v.field("min_length_scale_extent", o.min_length_scale_extent,
          {.unit = "",
           .doc = "Smallest length scale also in extents of the training points (0: none; gp "
                  "uses at least 0.25)",
           .choices = {},
           .range = kNonNegative});
  v.field("max_length_scale_factor", o.max_length_scale_factor,
          {.unit = "",
           .doc = "Largest length scale, in extents of the training points",
           .choices = {},
           .range = kPositive});
  v.field("max_signal_std_factor", o.max_signal_std_factor,
          {.unit = "",
           .doc = "Largest signal std, in RMS of the outputs about their mean",
           .choices = {},
           .range = kPositive});
  v.require(o.min_length_scale_extent <= o.max_length_scale_factor, "min_length_scale_extent",
            "<= max_length_scale_factor");
  v.group("rprop", "The optimizer", [&] { visit(v, o.rprop); });
}

void visit(OptionVisitor& v, ReductionOptions& o) {
  v.field("budget", o.budget,
          {.unit = "",
           .doc = "At most this many pairs after reduction, >= 3",
           .choices = {},
           .range = kPairBudget});
}

void visit(OptionVisitor& v, ScanMatchOptions& o) {
  v.field("max_iterations", o.max_iterations,
          {.unit = "",
           .doc = "Gauss-Newton iterations at most (>= 1)",
           .choices = {},
           .range = between(1, 1e4)});
  v.field("max_correspondence", o.max_correspondence,
          {.unit = "m",
           .doc = "Correspondences farther than this are ignored",
           .choices = {},
           .range = kPositive});
  v.field("min_correspondence", o.min_correspondence,
          {.unit = "m",
           .doc = "Smallest correspondence gate (the gate shrinks to it, <= max_correspondence)",
           .choices = {},
           .range = kPositive});
  v.field("robust_scale", o.robust_scale,
          {.unit = "m",
           .doc = "Scale of the Geman-McClure weight (c^2 / (c^2 + r^2))^2",
           .choices = {},
           .range = kPositive});
  v.field("inlier_distance", o.inlier_distance,
          {.unit = "m",
           .doc = "A residual this small is an inlier",
           .choices = {},
           .range = kPositive});
  v.field("min_inliers", o.min_inliers,
          {.unit = "",
           .doc = "Accept a match only with at least this many inliers",
           .choices = {},
           .range = at_least(1)});
  v.field("min_inlier_fraction", o.min_inlier_fraction,
          {.unit = "",
           .doc = "Accept a match only when its inliers are at least this share of the endpoints",
           .choices = {},
           .range = kShare});
  v.field("min_constraint", o.min_constraint,
          {.unit = "",
           .doc = "Least share of the inliers' wall normals along the weakest direction (0 to 0.5)",
           .choices = {},
           .range = between(0, 0.5)});
  v.field("max_correction", o.max_correction,
          {.unit = "m",
           .doc = "A match moving the pose farther fails",
           .choices = {},
           .range = kPositive});
  v.field("max_heading_correction", o.max_heading_correction,
          {.unit = "rad", .doc = "Likewise for the heading", .choices = {}, .range = kPositive});
  v.field("tolerance", o.tolerance,
          {.unit = "rad",
           .doc = "Stop when a step moves less than this (metres and radians)",
           .choices = {},
           .range = kPositive});
  v.require(o.min_correspondence <= o.max_correspondence, "min_correspondence",
            "<= max_correspondence");
}

void visit(OptionVisitor& v, RecoveryOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "", .doc = "Detect divergence and recover (false: never)", .choices = {}});
  v.field("min_beam_likelihood", o.min_beam_likelihood,
          {.unit = "",
           .doc = "A scan is bad when the mean beam likelihood is below this",
           .choices = {},
           .range = kShare});
  v.field("max_bad_scans", o.max_bad_scans,
          {.unit = "",
           .doc = "This many consecutive bad scans while tracking mean diverged (>= 1)",
           .choices = {},
           .range = at_least(1)});
  v.field("max_position_std", o.max_position_std,
          {.unit = "m",
           .doc = "After having converged, a position spread above this means diverged (the cloud "
                  "has exploded)",
           .choices = {},
           .range = kNonNegative});
  v.field("min_fast_slow_ratio", o.min_fast_slow_ratio,
          {.unit = "",
           .doc = "After converging, w_fast / w_slow below this means diverged (0: off)",
           .choices = {},
           .range = kShare});
  v.field("alpha_slow", o.alpha_slow,
          {.unit = "",
           .doc = "Per-scan smoothing of the long-term likelihood w_slow (augmented MCL)",
           .choices = {},
           .range = kPositiveShare});
  v.field("alpha_fast", o.alpha_fast,
          {.unit = "",
           .doc = "Per-scan smoothing of the short-term average likelihood w_fast, in (0, 1], > "
                  "alpha_slow",
           .choices = {},
           .range = kPositiveShare});
  v.field(
      "max_augmented_fraction", o.max_augmented_fraction,
      {.unit = "",
       .doc = "While tracking, inject global particles up to this share (augmented MCL, 0: off)",
       .choices = {},
       .range = kShare});
  v.field("recovery_fraction", o.recovery_fraction,
          {.unit = "",
           .doc = "Share of the particles replaced on every recovering scan, in (0, 1]",
           .choices = {},
           .range = kPositiveShare});
  v.field("global_share", o.global_share,
          {.unit = "",
           .doc = "Share of the replaced particles drawn over the whole free space",
           .choices = {},
           .range = kShare});
  v.field("initial_radius", o.initial_radius,
          {.unit = "m",
           .doc = "Radius of the disc around the anchor when the anchor is set (> 0)",
           .choices = {},
           .range = kPositive});
  v.field(
      "initial_heading_spread", o.initial_heading_spread,
      {.unit = "rad",
       .doc =
           "Heading spread (uniform +-) around the anchor's heading when the anchor is set (> 0)",
       .choices = {},
       .range = kPositive});
  v.field("radius_growth", o.radius_growth,
          {.unit = "",
           .doc = "Growth of the recovery radius and heading spread per fruitless scan",
           .choices = {},
           .range = at_least(1.0)});
  v.field("max_radius", o.max_radius,
          {.unit = "m",
           .doc = "The radius stops growing here (>= initial_radius)",
           .choices = {},
           .range = kPositive});
  v.field("max_recovery_scans", o.max_recovery_scans,
          {.unit = "",
           .doc = "Recovering scans after which a filter that knows its free space restarts global "
                  "localization (>= 1)",
           .choices = {},
           .range = at_least(1)});
  v.require(o.alpha_fast > o.alpha_slow, "alpha_fast", "> alpha_slow");
  v.require(o.max_radius >= o.initial_radius, "max_radius", ">= initial_radius");
}

void visit(OptionVisitor& v, ConvergenceOptions& o) {
  v.field("max_position_std", o.max_position_std,
          {.unit = "m",
           .doc = "PoseEstimate::position_std at most this",
           .choices = {},
           .range = kPositive});
  v.field("max_heading_std", o.max_heading_std,
          {.unit = "rad",
           .doc = "PoseEstimate::heading_std at most this",
           .choices = {},
           .range = kPositive});
  v.field("max_scale_std", o.max_scale_std,
          {.unit = "",
           .doc = "PoseEstimate::scale_std at most this",
           .choices = {},
           .range = kPositive});
  v.field(
      "min_ess_ratio", o.min_ess_ratio,
      {.unit = "", .doc = "N_eff / N at least this, in [0, 1]", .choices = {}, .range = kShare});
  v.field("min_beam_likelihood", o.min_beam_likelihood,
          {.unit = "",
           .doc = "Mean beam likelihood at the mean pose and scale at least this, in [0, 1]",
           .choices = {},
           .range = kShare});
  v.field(
      "min_converged_scans", o.min_converged_scans,
      {.unit = "",
       .doc =
           "Consecutive scans meeting every criterion before the filter counts as converged (>= 1)",
       .choices = {},
       .range = at_least(1)});
  v.field("max_failed_scans", o.max_failed_scans,
          {.unit = "",
           .doc = "Consecutive failing scans before a converged filter is no longer converged",
           .choices = {},
           .range = at_least(1)});
  v.field("rejoin_window", o.rejoin_window,
          {.unit = "",
           .doc = "A filter that failed at most this many scans since it was converged rejoins "
                  "after min_rejoin_scans good scans (0: never)",
           .choices = {},
           .range = at_least(0)});
  v.field("min_rejoin_scans", o.min_rejoin_scans,
          {.unit = "",
           .doc = "Consecutive scans meeting every criterion for such a filter to rejoin",
           .choices = {},
           .range = at_least(1)});
  v.field("max_blind_scans", o.max_blind_scans,
          {.unit = "scans",
           .doc = "Consecutive scans the map cannot judge (they end where it knows nothing) "
                  "after which a converged filter no longer counts as converged (0: never)",
           .choices = {},
           .range = at_least(0)});
}

void visit(OptionVisitor& v, HypothesisSeedingOptions& o) {
  v.field("position_step", o.position_step,
          {.unit = "m",
           .doc = "Step of the lattice of positions over the free space",
           .choices = {},
           .range = between(0.001, 1e3)});
  v.field("headings", o.headings,
          {.unit = "",
           .doc = "Headings per lattice position, evenly spaced",
           .choices = {},
           .range = between(1, 3600)});
  v.field("scales", o.scales,
          {.unit = "",
           .doc = "Scales per lattice position, over the scale range",
           .choices = {},
           .range = between(1, 1000)});
  v.field("keep", o.keep,
          {.unit = "",
           .doc = "Best hypotheses kept as particles",
           .choices = {},
           .range = between(1, 1e7)});
  v.field("max_hypotheses", o.max_hypotheses,
          {.unit = "",
           .doc = "Hypotheses scored at most (>= 1)",
           .choices = {},
           .range = between(1, 1e10)});
  v.field("batch", o.batch,
          {.unit = "",
           .doc = "Hypotheses per observation-model call (bounds memory)",
           .choices = {},
           .range = between(1, 1e6)});
  v.field("jitter", o.jitter,
          {.unit = "", .doc = "Spread each kept hypothesis over its lattice cell", .choices = {}});
}

void visit(OptionVisitor& v, FreeSpaceOptions& o) {
  v.field("max_wall_distance", o.max_wall_distance,
          {.unit = "m",
           .doc = "Global sampling keeps free cells this close to a wall (0: every free cell)",
           .choices = {},
           .range = kNonNegative});
}

void visit(OptionVisitor& v, MotionNoise& o) {
  v.field("alpha1", o.alpha1,
          {.unit = "",
           .doc = "Rotation noise from rotation (rad^2/rad^2)",
           .choices = {},
           .range = kNoise});
  v.field("alpha2", o.alpha2,
          {.unit = "",
           .doc = "Rotation noise from translation (rad^2/m^2)",
           .choices = {},
           .range = kNoise});
  v.field("alpha3", o.alpha3,
          {.unit = "",
           .doc = "Translation noise from translation (m^2/m^2)",
           .choices = {},
           .range = kNoise});
  v.field("alpha4", o.alpha4,
          {.unit = "",
           .doc = "Translation noise from rotation (m^2/rad^2)",
           .choices = {},
           .range = kNoise});
}

void visit(OptionVisitor& v, AutoOptions& o) {
  v.field("candidates", o.candidates,
          {.unit = "",
           .doc = "The models compared, cheapest first (ties go to the earlier one)",
           .choices = {}});
  v.group("cv", "How they are compared", [&] { visit(v, o.cv); });
  v.field("tie_standard_errors", o.tie_standard_errors,
          {.unit = "",
           .doc = "By runs: an earlier candidate this many standard errors from the lowest "
                  "score is chosen instead (0: the lowest always)",
           .choices = {},
           .range = between(0, 100)});
}

void visit(OptionVisitor& v, ThinPlateSplineModelOptions& o) {
  v.field("regularization", o.regularization,
          {.unit = "m^2",
           .doc = "Regularization weight lambda (null: chosen by cross-validation)",
           .choices = {},
           .range = between(0, 1e12)});
  v.field("tuning_pairs", o.tuning_pairs,
          {.unit = "",
           .doc = "Subsample size of the lambda choice",
           .choices = {},
           .range = between(20, 1e5)});
  v.field("robust_max_pairs", o.robust_max_pairs,
          {.unit = "",
           .doc = "At most this many pairs (hand-picked) are refitted robustly (0: never)",
           .choices = {},
           .range = between(0, 1e4)});
  v.field("robust_iterations", o.robust_iterations,
          {.unit = "",
           .doc = "Reweightings of the robust refit",
           .choices = {},
           .range = between(0, 100)});
  v.field("robust_cutoff", o.robust_cutoff,
          {.unit = "",
           .doc = "Leave-one-out errors above this many times their median are down-weighted",
           .choices = {},
           .range = kPositive});
  v.group("lattice", "For mapping many points at once", [&] { visit(v, o.lattice); });
  v.field("lattice_from", o.lattice_from,
          {.unit = "",
           .doc = "Batches at least this large use the lattice",
           .choices = {},
           .range = at_least(0)});
}

void visit(OptionVisitor& v, GaussianProcessOptions& o) {
  // hyperparameters are not options: fitted models tune them (fit them by hand in code).
  v.group("tuning", "Subsample, bounds and RPROP settings of the tuning",
          [&] { visit(v, o.tuning); });
  v.group("prediction", "Lattice and threads of the fitted model", [&] { visit(v, o.prediction); });
  v.field("max_points", o.max_points,
          {.unit = "",
           .doc = "Refuse more training points than this (K takes 8 N^2 bytes and N^3 / 3 flops)",
           .choices = {},
           .range = kDensePoints});
}

void visit(OptionVisitor& v, LocalTransformsOptions& o) {
  enum_field(v, "kind", o.kind,
             {{"similarity", TransformKind::similarity},
              {"rigid", TransformKind::rigid},
              {"affine", TransformKind::affine}},
             "The family of each local transform");
  v.field("cell_size", o.cell_size,
          {.unit = "m",
           .doc = "Finest clustering cells (0: the extent / 12)",
           .choices = {},
           .range = kDistance});
  v.field("levels", o.levels,
          {.unit = "",
           .doc = "Coarser levels (cells doubled each) over which clusters merge",
           .choices = {},
           .range = between(0, 30)});
  v.field("agreement", o.agreement,
          {.unit = "m",
           .doc = "A pair agrees with a transform within this distance",
           .choices = {},
           .range = kPositive});
  v.field("min_cluster_pairs", o.min_cluster_pairs,
          {.unit = "", .doc = "Smaller clusters are dropped", .choices = {}, .range = at_least(2)});
  v.field("hypotheses", o.hypotheses,
          {.unit = "",
           .doc = "Seeded minimal samples tried per cluster in a cell",
           .choices = {},
           .range = between(1, 1e6)});
  v.field("weight_power", o.weight_power,
          {.unit = "",
           .doc = "Blend weights w_k = 1 / d^power of the distance to each cluster",
           .choices = {},
           .range = above_to(0.0, 100)});
  v.field("budget", o.budget,
          {.unit = "",
           .doc = "Pairs kept (spatial binning, the pairs of a cell averaged) before clustering",
           .choices = {},
           .range = kPairBudget});
}

void visit(OptionVisitor& v, LinearCombinationOptions& o) {
  v.field("neighbours", o.neighbours,
          {.unit = "",
           .doc = "Nearest plan points searched for a triangle (first round)",
           .choices = {},
           .range = between(3, kMaxNeighbours)});
  v.field("min_angle_deg", o.min_angle_deg,
          {.unit = "deg",
           .doc = "Smallest angle a usable triangle may have",
           .choices = {},
           .range = OptionRange{.min = 0.0, .max = 60.0}});
  v.field(
      "budget", o.budget,
      {.unit = "", .doc = "Pairs kept after spatial binning", .choices = {}, .range = kPairBudget});
}

void visit(OptionVisitor& v, RansacOptions& o) {
  enum_field(v, "kind", o.kind,
             {{"similarity", TransformKind::similarity},
              {"rigid", TransformKind::rigid},
              {"affine", TransformKind::affine}},
             "The family fitted");
  enum_field(v, "reflection", o.reflection,
             {{"forbid", Reflection::forbid},
              {"allow", Reflection::allow},
              {"require", Reflection::require}},
             "Similarity and rigid");
  v.field("inlier_threshold", o.inlier_threshold,
          {.unit = "m",
           .doc = "A pair is an inlier when |T p - q| <= this (null: adapted to the pairs' noise)",
           .choices = {},
           .range = kPositive});
  v.field("threshold_sigmas", o.threshold_sigmas,
          {.unit = "",
           .doc = "Adaptive threshold: this many times the estimated noise scale sigma (per axis)",
           .choices = {},
           .range = above_to(0.0, 100)});
  v.field(
      "search_threshold_fraction", o.search_threshold_fraction,
      {.unit = "",
       .doc = "Adaptive threshold: the hypothesis search's, as a share of the grid points' extent",
       .choices = {},
       .range = kPositiveShare});
  v.field("confidence", o.confidence,
          {.unit = "",
           .doc = "Wanted probability of one all-inlier sample, in (0, 1)",
           .choices = {},
           .range = kOpenShare});
  v.field("max_iterations", o.max_iterations,
          {.unit = "",
           .doc = "Minimal samples drawn at most",
           .choices = {},
           .range = between(1, 1e9)});
  v.field("min_iterations", o.min_iterations,
          {.unit = "",
           .doc = "Minimal samples drawn at least",
           .choices = {},
           .range = between(0, 1e9)});
  v.field("seed", o.seed,
          {.unit = "", .doc = "Same seed, same result", .choices = {}, .range = kSeed});
  v.field("preemptive_subset", o.preemptive_subset,
          {.unit = "",
           .doc = "Pairs (a fixed random subset) on which every hypothesis is scored",
           .choices = {},
           .range = at_least(1)});
  v.field("verify_count", o.verify_count,
          {.unit = "",
           .doc = "Best hypotheses on that subset re-scored on the verification subset",
           .choices = {},
           .range = at_least(1)});
  v.field("verify_subset", o.verify_subset,
          {.unit = "",
           .doc = "Pairs on which the best hypotheses are re-scored and refitted",
           .choices = {},
           .range = at_least(1)});
  v.field("max_refit_passes", o.max_refit_passes,
          {.unit = "",
           .doc = "Passes over all pairs (classify, then refit) at most",
           .choices = {},
           .range = between(1, 1000)});
  v.field("min_sample_separation", o.min_sample_separation,
          {.unit = "",
           .doc = "Minimal samples closer than this share of the extent are rejected",
           .choices = {},
           .range = OptionRange{.min = 0.0, .max = 1.0, .min_open = false}});
  v.field("threads", o.threads,
          {.unit = "",
           .doc = "Threads of the passes over all pairs",
           .choices = {},
           .range = kOneOrTwo});
  v.require(o.min_iterations <= o.max_iterations, "min_iterations", "<= max_iterations");
}

void visit(OptionVisitor& v, MappingCommonOptions& o) {
  v.field("extrapolation_distance", o.extrapolation_distance,
          {.unit = "m",
           .doc = "A point farther than this from every pair is flagged extrapolated",
           .choices = {},
           .range = kDistance});
  v.field("max_error", o.max_error,
          {.unit = "m",
           .doc = "A point whose 95% error bound (2 std_m) exceeds this is flagged uncertain",
           .choices = {},
           .range = above_to(0.0, kMaxCoordinate)});
  v.group("reduction", "Pair budget of models that reduce their pairs",
          [&] { visit(v, o.reduction); });
  v.field("support_budget", o.support_budget,
          {.unit = "",
           .doc = "Pairs kept for confidence, hull and inverse start",
           .choices = {},
           .range = kPairBudget});
  v.field("inverse_tolerance", o.inverse_tolerance,
          {.unit = "",
           .doc = "Newton inverse: residual relative to the extent",
           .choices = {},
           .range = kOpenShare});
  v.field("inverse_max_iterations", o.inverse_max_iterations,
          {.unit = "",
           .doc = "Newton inverse: steps at most",
           .choices = {},
           .range = between(1, 1e4)});
  v.field("seed", o.seed,
          {.unit = "",
           .doc = "Randomness of the fit (RANSAC, subsampling)",
           .choices = {},
           .range = kSeed});
}

void visit(OptionVisitor& v, ScaleRange& o) {
  v.field("min", o.min,
          {.unit = "", .doc = "Smallest scale, > 0", .choices = {}, .range = kPositive});
  v.field("max", o.max,
          {.unit = "", .doc = "Largest scale, >= min", .choices = {}, .range = kPositive});
  v.require(o.max >= o.min, "max", ">= min");
}

void visit(OptionVisitor& v, PlanRegistrationOptions& o) {
  v.group("seeding", "The lattice", [&] { visit(v, o.seeding); });
  v.field("coarse_points", o.coarse_points,
          {.unit = "",
           .doc = "The lattice is scored with this many of the submap's points (evenly thinned)",
           .choices = {},
           .range = between(1, 1e7)});
  v.field("runner_up_distance", o.runner_up_distance,
          {.unit = "m",
           .doc = "The runner-up is the best hypothesis this far from the best...",
           .choices = {},
           .range = kNonNegative});
  v.field("runner_up_heading", o.runner_up_heading,
          {.unit = "rad", .doc = "... or turned this much", .choices = {}, .range = kNonNegative});
  v.field(
      "min_scale", o.min_scale,
      {.unit = "", .doc = "Refined scales are kept above this", .choices = {}, .range = kPositive});
  v.field(
      "seed", o.seed,
      {.unit = "", .doc = "Randomness of the lattice's seeding", .choices = {}, .range = kSeed});
}

void visit(OptionVisitor& v, SubmapOptions& o) {
  v.field("bin", o.bin,
          {.unit = "m",
           .doc = "One point per bin of this size (> 0)",
           .choices = {},
           .range = between(0.001, 1e3)});
  v.field("max_points", o.max_points,
          {.unit = "",
           .doc = "At most this many points, evenly thinned (>= 1)",
           .choices = {},
           .range = between(1, 1e7)});
  v.field("max_range", o.max_range,
          {.unit = "m", .doc = "Longer readings are left out", .choices = {}, .range = kPositive});
}

void visit(OptionVisitor& v, VisibleWallsOptions& o) {
  v.field("gap_closing", o.gap_closing,
          {.unit = "m",
           .doc = "Door-sized gaps (up to twice this) are closed while the outside is flooded",
           .choices = {},
           .range = between(0, 10)});
  v.field("min_clearance", o.min_clearance,
          {.unit = "m",
           .doc = "Free space is a room when some cell of it is this far from every wall",
           .choices = {},
           .range = between(0, 100)});
  v.field("reach", o.reach,
          {.unit = "m",
           .doc = "A wall cell is visible when free room space lies within this distance",
           .choices = {},
           .range = between(0, 100)});
  v.field("max_thickness", o.max_thickness,
          {.unit = "m",
           .doc = "A wall cell beyond reach of every room is hidden only this close to one (a "
                  "wall's far face); walls far from every room stay",
           .choices = {},
           .range = between(0, 100)});
}

void visit(OptionVisitor& v, FilterRunnerOptions& o) {
  v.field("update_min_translation", o.update_min_translation,
          {.unit = "m",
           .doc = "Odometry travel before the filter is updated again",
           .choices = {},
           .range = kNonNegative});
  v.field("update_min_rotation", o.update_min_rotation,
          {.unit = "rad",
           .doc = "Turn of odometry before the filter is updated again",
           .choices = {},
           .range = kNonNegative});
  v.field("improved_proposal", o.improved_proposal,
          {.unit = "",
           .doc = "Improved proposal while tracking (Grisetti, Stachniss, Burgard 2007)",
           .choices = {}});
  v.field("refine", o.refine,
          {.unit = "",
           .doc = "Match each scan of a converged filter onto the walls from its mean pose (the "
                  "refined pose pairs are made from)",
           .choices = {}});
  v.group("match", "Both uses of scan matching", [&] { visit(v, o.match); });
  v.field("beam_tolerance", o.beam_tolerance,
          {.unit = "m",
           .doc = "Beams are matched when they reach the first wall along them within this",
           .choices = {},
           .range = kPositive});
  v.group("match_observation", "Beams per scan of the matching",
          [&] { visit(v, o.match_observation); });
  v.field(
      "threads", o.threads,
      {.unit = "", .doc = "Threads of the observation model", .choices = {}, .range = kThreads});
  v.group("guided_noise", "Noise of a motion taken from a guide (another filter's poses)",
          [&] { visit(v, o.guided_noise); });
  v.field("guide_min_translation", o.guide_min_translation,
          {.unit = "m",
           .doc = "Only steps of at least this much odometry (or guide_min_rotation) are guided",
           .choices = {},
           .range = kNonNegative});
  v.field("guide_min_rotation", o.guide_min_rotation,
          {.unit = "rad", .doc = "Likewise for the turn", .choices = {}, .range = kNonNegative});
  v.field("guide_max_translation", o.guide_max_translation,
          {.unit = "m",
           .doc = "A guide's motion farther than this (plus a share of the step) from the "
                  "odometry's is not trusted",
           .choices = {},
           .range = kNonNegative});
  v.field("guide_translation_share", o.guide_translation_share,
          {.unit = "",
           .doc = "That share of the odometry's step",
           .choices = {},
           .range = kNonNegative});
  v.field("guide_max_rotation", o.guide_max_rotation,
          {.unit = "rad",
           .doc = "Likewise for the turn (plus per metre of the step, plus a share of the turn)",
           .choices = {},
           .range = kNonNegative});
  v.field("guide_rotation_per_metre", o.guide_rotation_per_metre,
          {.unit = "rad/m",
           .doc = "That allowance per metre of the step",
           .choices = {},
           .range = kNonNegative});
  v.field("guide_rotation_share", o.guide_rotation_share,
          {.unit = "",
           .doc = "That share of the odometry's turn",
           .choices = {},
           .range = kNonNegative});
}

void visit(OptionVisitor& v, ObservationOptions& o) {
  v.field("max_beams", o.max_beams,
          {.unit = "",
           .doc = "Keep at most this many returns, evenly spread over the scan",
           .choices = {},
           .range = between(1, 1e5)});
}

void visit(OptionVisitor& v, LikelihoodFieldOptions& o) {
  v.field("sigma_hit", o.sigma_hit,
          {.unit = "m",
           .doc = "Spread of an endpoint about the wall it hit",
           .choices = {},
           .range = kPositive});
  v.field("z_hit", o.z_hit,
          {.unit = "",
           .doc = "Weight of the Gaussian part, >= 0",
           .choices = {},
           .range = kNonNegative});
  v.field("z_rand", o.z_rand,
          {.unit = "",
           .doc = "Likelihood of an endpoint far from every wall (the floor)",
           .choices = {},
           .range = kPositive});
  v.field("max_distance", o.max_distance,
          {.unit = "m",
           .doc = "The distance field is capped here",
           .choices = {},
           .range = above_to(0.0, 1e3)});
  v.field("beam_weight", o.beam_weight,
          {.unit = "",
           .doc = "Temperature: the scan's log-likelihood times this (< 1 against overconfidence)",
           .choices = {},
           .range = kPositive});
  v.field("unknown_is_free", o.unknown_is_free,
          {.unit = "",
           .doc = "Endpoints in unknown cells score by their distance to a wall like free ones",
           .choices = {}});
  v.field("known_margin", o.known_margin,
          {.unit = "m",
           .doc = "Endpoints farther than this from every observed cell say nothing",
           .choices = {},
           .range = kNonNegative});
  v.field("min_known_share", o.min_known_share,
          {.unit = "",
           .doc = "A scan says nothing when fewer than this share of its endpoints are known",
           .choices = {},
           .range = kShare});
}

void visit(OptionVisitor& v, ParticleFilterOptions& o) {
  v.group("motion", "Odometry noise alpha1..alpha4 (world metres and radians)",
          [&] { visit(v, o.motion); });
  v.field(
      "scale_walk", o.scale_walk,
      {.unit = "",
       .doc = "Random walk of the particles' scales, per square root of a world metre travelled",
       .choices = {},
       .range = kNonNegative});
  v.field("tracking_particles", o.tracking_particles,
          {.unit = "",
           .doc = "Particles while tracking (>= 1)",
           .choices = {},
           .range = between(1, 1e6)});
  v.field("global_particles", o.global_particles,
          {.unit = "",
           .doc = "Particles of global localization",
           .choices = {},
           .range = between(1, 1e7)});
  v.field("resample_ess_ratio", o.resample_ess_ratio,
          {.unit = "",
           .doc = "Resample when N_eff / N falls below this (1: every scan)",
           .choices = {},
           .range = kShare});
  v.group("free_space", "Which free cells global sampling and injection use",
          [&] { visit(v, o.free_space); });
  v.group("seeding", "Global localization from the best hypotheses of a lattice",
          [&] { visit(v, o.seeding); });
  v.group("convergence", "When the filter counts as converged", [&] { visit(v, o.convergence); });
  v.group("recovery", "Divergence detection and recovery", [&] { visit(v, o.recovery); });
}

void visit(OptionVisitor& v, MappingOptions& o) {
  v.field("model", o.model,
          {.unit = "",
           .doc = "The model (one of lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps, auto)",
           .choices = {}});
  v.group("common", "Shared", [&] { visit(v, o.common); });
  v.group("ransac", "Gt variants (and gpgt's global part)", [&] { visit(v, o.ransac); });
  v.field("gpgt_inlier_threshold", o.gpgt_inlier_threshold,
          {.unit = "m",
           .doc = "The RANSAC inlier distance of gpgt's similarity (null: adapted to the "
                  "pairs' noise; a fixed one should be wide: the GP takes the bends)",
           .choices = {},
           .range = kPositive});
  v.group("lc", "Lc", [&] { visit(v, o.lc); });
  v.group("ct", "Ct", [&] { visit(v, o.ct); });
  v.group("gp", "Gp and gpgt", [&] { visit(v, o.gp); });
  v.group("tps", "Tps", [&] { visit(v, o.tps); });
  v.group("auto_select", "Auto", [&] { visit(v, o.auto_select); });
  v.group("uncertainty", "Every model's std_m, fitted on its blocked cross-validation",
          [&] { visit(v, o.uncertainty); });
}

void visit(OptionVisitor& v, PosePullOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "",
           .doc = "Measure how far the plan's poses stand ahead of the gridmap's along the "
                  "robot's heading, from places revisited facing another way, and take it out "
                  "of the pairs when it is measured well (false: the pairs as matched)",
           .choices = {}});
  v.field("radius", o.radius,
          {.unit = "m",
           .doc = "Two scans whose gridmap poses lie this close are at one place",
           .choices = {},
           .range = kPositive});
  v.field("min_turn", o.min_turn,
          {.unit = "rad",
           .doc = "... and their headings differ by at least this much",
           .choices = {},
           .range = between(0.1, 3.14159)});
  v.field("min_time_apart", o.min_time_apart,
          {.unit = "s",
           .doc = "... and they are at least this far apart in time",
           .choices = {},
           .range = kNonNegative});
  v.field("min_scans", o.min_scans,
          {.unit = "",
           .doc = "Scans compared with a revisit needed before the pull is taken out",
           .choices = {},
           .range = at_least(1)});
  v.field("max_std", o.max_std,
          {.unit = "m",
           .doc = "The pull is taken out only when its standard error is at most this",
           .choices = {},
           .range = kNonNegative});
  v.field("max_pull", o.max_pull,
          {.unit = "m",
           .doc = "... and it is at most this large",
           .choices = {},
           .range = kNonNegative});
}

void visit(OptionVisitor& v, OutlierScanOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "",
           .doc = "Drop scans whose pairs disagree with the rest (false: keep every scan)",
           .choices = {}});
  v.field("cell", o.cell,
          {.unit = "m",
           .doc = "Pairs are compared within cells of this size",
           .choices = {},
           .range = between(0.01, 1e3)});
  v.field("max_deviation", o.max_deviation,
          {.unit = "m",
           .doc = "A scan farther than this from its cells' consensus loses its pairs",
           .choices = {},
           .range = kPositive});
  v.field("min_cell_pairs", o.min_cell_pairs,
          {.unit = "",
           .doc = "Other scans' pairs a cell needs for its consensus to count",
           .choices = {},
           .range = at_least(0)});
  v.field("min_pairs", o.min_pairs,
          {.unit = "", .doc = "Pairs needed at all", .choices = {}, .range = at_least(0)});
  v.field("similarity_inlier_threshold", o.similarity_inlier_threshold,
          {.unit = "m",
           .doc = "The RANSAC inlier distance of the similarity the residuals are taken from",
           .choices = {},
           .range = kPositive});
  v.field("min_scan_pairs", o.min_scan_pairs,
          {.unit = "",
           .doc = "Pairs of a scan that must have a consensus to compare with before the scan can "
                  "be dropped",
           .choices = {},
           .range = at_least(0)});
  v.field("max_gross_residual", o.max_gross_residual,
          {.unit = "m",
           .doc = "A scan whose pairs lie farther than this from the similarity is dropped, "
                  "consensus or not",
           .choices = {},
           .range = kPositive});
  v.field("gross_residual_scales", o.gross_residual_scales,
          {.unit = "",
           .doc = "The gross limit is at least this many times the pairs' median residual",
           .choices = {},
           .range = kPositive});
  v.field("max_gross_fraction", o.max_gross_fraction,
          {.unit = "",
           .doc = "When more pairs than this fraction are beyond the gross limit, the map is "
                  "distorted and none is dropped for it",
           .choices = {},
           .range = kShare});
}

void visit(OptionVisitor& v, PairExtractionOptions& o) {
  v.field("beam_step", o.beam_step,
          {.unit = "",
           .doc = "Keep every k-th beam of a scan (beam subsampling)",
           .choices = {},
           .range = between(1, 1e4)});
  v.field("max_pairs_per_scan", o.max_pairs_per_scan,
          {.unit = "",
           .doc = "Then at most this many pairs per scan, evenly spread",
           .choices = {},
           .range = at_least(1)});
  v.field("max_range", o.max_range,
          {.unit = "m", .doc = "Longer readings make no pairs", .choices = {}, .range = kPositive});
  v.field("max_wall_distance", o.max_wall_distance,
          {.unit = "m",
           .doc = "An endpoint must lie this close to a wall of each map (WallField::distance: "
                  "a raster plan's ink edge where scans meet it there)",
           .choices = {},
           .range = kPositive});
}

void visit(OptionVisitor& v, ScaleRefitOptions& o) {
  v.field(
      "enabled", o.enabled,
      {.unit = "", .doc = "Refit the scale jointly with the refined plan poses", .choices = {}});
  enum_field(v, "surface_shift", o.surface_shift,
             {{"auto", SurfaceShift::automatic},
              {"always", SurfaceShift::always},
              {"never", SurfaceShift::never}},
             "Fit with the scale a shift of every plan wall's surface towards the laser (faces in "
             "front of the drawn lines or ink): auto uses it where at least min_shift, always "
             "whatever its size");
  v.field("refit_registered_scale", o.refit_registered_scale,
          {.unit = "",
           .doc = "Refit also a scale the maps' registration gave, where the surface shift is "
                  "fitted",
           .choices = {}});
  v.field("raise_registered_scale", o.raise_registered_scale,
          {.unit = "",
           .doc = "Where the shift is not used and the maps' registration gave the scale without "
                  "meeting the outer walls' faces, use the scale refitted alone when it is higher",
           .choices = {}});
  v.field("min_shift", o.min_shift,
          {.unit = "m",
           .doc = "With auto, the fitted shift is used only where it is at least this large "
                  "(else the scale alone, and a registered scale kept)",
           .choices = {},
           .range = kNonNegative});
  v.field("min_shift_pixels", o.min_shift_pixels,
          {.unit = "",
           .doc = "With auto, on a raster plan the shift is used only where it is also at least "
                  "this many of its pixels (within a pixel its ink's edges do not place the faces)",
           .choices = {},
           .range = kNonNegative});
  v.field("min_scans", o.min_scans,
          {.unit = "",
           .doc = "Matched scans the refit needs, else the search's scale stays",
           .choices = {},
           .range = at_least(1)});
  v.field("max_iterations", o.max_iterations,
          {.unit = "",
           .doc = "Iterations of the joint Gauss-Newton at most",
           .choices = {},
           .range = between(1, 1e4)});
  v.field("jackknife_blocks", o.jackknife_blocks,
          {.unit = "",
           .doc = "Blocks of scans for the scale's standard deviation",
           .choices = {},
           .range = between(2, 1e4)});
  v.field("max_change", o.max_change,
          {.unit = "",
           .doc = "A refit farther than this share from the searched scale is not trusted (too few "
                  "or bad scans)",
           .choices = {},
           .range = kPositive});
  v.field("retrack_change", o.retrack_change,
          {.unit = "",
           .doc = "Track the plan again when the refit moves the scale by more than this share",
           .choices = {},
           .range = kNonNegative});
  v.field("max_plan_passes", o.max_plan_passes,
          {.unit = "",
           .doc = "Tracking passes of the plan filter at most",
           .choices = {},
           .range = between(1, 100)});
  v.field("retrack_min_share", o.retrack_min_share,
          {.unit = "",
           .doc = "A pass tracked again is kept only where at least this share of the last "
                  "pass's matched scans matched again (else the last pass's poses and scale stay)",
           .choices = {},
           .range = between(0, 1)});
}

void visit(OptionVisitor& v, SubmapCheckOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "",
           .doc = "Re-place the plan filter where the last scans' submap (seen from the gridmap "
                  "filter's poses) fits the plan clearly better than where it is",
           .choices = {}});
  v.field(
      "every", o.every,
      {.unit = "scans", .doc = "Scans between two checks", .choices = {}, .range = at_least(1)});
  v.field("window", o.window,
          {.unit = "scans",
           .doc = "Scans back the submap may reach",
           .choices = {},
           .range = at_least(1)});
  v.field("spacing", o.spacing,
          {.unit = "m",
           .doc = "A scan joins the submap when the gridmap pose moved this far since the last "
                  "one that joined",
           .choices = {},
           .range = kNonNegative});
  v.field("spacing_heading", o.spacing_heading,
          {.unit = "rad", .doc = "... or turned this much", .choices = {}, .range = kNonNegative});
  v.field("max_scans", o.max_scans,
          {.unit = "scans",
           .doc = "At most this many (the newest) make the submap",
           .choices = {},
           .range = at_least(1)});
  v.field("min_scans", o.min_scans,
          {.unit = "scans", .doc = "Fewer: no check", .choices = {}, .range = at_least(1)});
  v.group("submap", "The submap's points", [&] { visit(v, o.submap); });
  v.field("search_distance", o.search_distance,
          {.unit = "m",
           .doc = "Shifts searched each way around the plan filter's pose",
           .choices = {},
           .range = between(0, 1000)});
  v.field(
      "search_step", o.search_step,
      {.unit = "m", .doc = "Their lattice's step", .choices = {}, .range = between(0.001, 1000)});
  v.field("search_heading", o.search_heading,
          {.unit = "rad",
           .doc = "Turns searched each way (about the robot)",
           .choices = {},
           .range = between(0, 3.2)});
  v.field("heading_step", o.heading_step,
          {.unit = "rad", .doc = "Their step", .choices = {}, .range = between(0.0001, 3.2)});
  v.field("coarse_points", o.coarse_points,
          {.unit = "",
           .doc = "Submap points the lattice is scored with (all of them refine the best)",
           .choices = {},
           .range = between(1, 1e7)});
  v.field("min_shift", o.min_shift,
          {.unit = "m",
           .doc = "The plan filter is re-placed at the best placement at least this far from its "
                  "pose",
           .choices = {},
           .range = kPositive});
  v.field("min_gain", o.min_gain,
          {.unit = "",
           .doc = "... when that explains at least this share more of the submap than the best "
                  "nearer",
           .choices = {},
           .range = kShare});
  v.field("max_from_registration", o.max_from_registration,
          {.unit = "m",
           .doc = "A placement farther than this from where the run's global registration puts "
                  "the robot is not taken",
           .choices = {},
           .range = kPositive});
  v.field("confirmations", o.confirmations,
          {.unit = "",
           .doc = "Checks in a row that must find the better placement before the plan filter is "
                  "re-placed",
           .choices = {},
           .range = at_least(1)});
}

void visit(OptionVisitor& v, DualCheckOptions& o) {
  v.field("local_window", o.local_window,
          {.unit = "",
           .doc = "Scans (pose pairs) the local registration is fitted to",
           .choices = {},
           .range = at_least(2)});
  v.field("local_min_pairs", o.local_min_pairs,
          {.unit = "",
           .doc = "Pose pairs the local registration needs",
           .choices = {},
           .range = at_least(2)});
  v.field("local_max_age", o.local_max_age,
          {.unit = "scans",
           .doc = "The local registration stays valid this long without news",
           .choices = {},
           .range = at_least(1)});
  v.field("local_distance", o.local_distance,
          {.unit = "m",
           .doc = "A plan pose farther than this from the local registration's disagrees",
           .choices = {},
           .range = kPositive});
  v.field("local_distance_growth", o.local_distance_growth,
          {.unit = "m/m",
           .doc = "local_distance grows by this per metre from the poses the local registration "
                  "was fitted on",
           .choices = {},
           .range = kNonNegative});
  v.field("local_heading", o.local_heading,
          {.unit = "rad", .doc = "Likewise for the heading", .choices = {}, .range = kPositive});
  v.field("local_reinitialize_distance", o.local_reinitialize_distance,
          {.unit = "m",
           .doc = "Re-initialize the plan filter when it disagrees locally by more than this",
           .choices = {},
           .range = kPositive});
  v.field("local_reinitialize_heading", o.local_reinitialize_heading,
          {.unit = "rad", .doc = "Likewise for the heading", .choices = {}, .range = kPositive});
  v.field(
      "consistency_distance", o.consistency_distance,
      {.unit = "m",
       .doc = "Without a fresh local registration: farther than this from the global one disagrees",
       .choices = {},
       .range = kPositive});
  v.field("consistency_heading", o.consistency_heading,
          {.unit = "rad", .doc = "Likewise for the heading", .choices = {}, .range = kPositive});
  v.field("consistency_scans", o.consistency_scans,
          {.unit = "scans",
           .doc = "Consecutive disagreeing scans before the plan filter is re-initialized",
           .choices = {},
           .range = at_least(1)});
  v.field("gross_factor", o.gross_factor,
          {.unit = "",
           .doc = "A plan filter off by this many times the re-initialization distance or heading",
           .choices = {},
           .range = kPositive});
  v.field("gross_scans", o.gross_scans,
          {.unit = "",
           .doc = "is re-initialized after this many such scans",
           .choices = {},
           .range = at_least(1)});
  v.field("reconverge_scans", o.reconverge_scans,
          {.unit = "scans",
           .doc = "Unconverged scans before the plan filter is re-initialized",
           .choices = {},
           .range = at_least(1)});
  v.field("mend_scans", o.mend_scans,
          {.unit = "scans",
           .doc = "A gridmap filter lost while the plan filter is sure restarts where the plan "
                  "says, given up after this many unconverged scans (0: never)",
           .choices = {},
           .range = at_least(0)});
  v.field("restart_when_lost", o.restart_when_lost,
          {.unit = "",
           .doc = "Re-initialize a plan filter that declares itself lost where the gridmap "
                  "filter says, at once",
           .choices = {}});
  v.field("local_reinitialize_sigma", o.local_reinitialize_sigma,
          {.unit = "m",
           .doc = "Spread of a cloud re-initialized by the local registration",
           .choices = {},
           .range = kNonNegative});
  v.field("local_reinitialize_heading_sigma", o.local_reinitialize_heading_sigma,
          {.unit = "rad", .doc = "Its heading spread", .choices = {}, .range = kNonNegative});
  v.field("reinitialize_sigma", o.reinitialize_sigma,
          {.unit = "m",
           .doc = "Spread of a cloud re-initialized by the global registration",
           .choices = {},
           .range = kNonNegative});
  v.field("reinitialize_heading_sigma", o.reinitialize_heading_sigma,
          {.unit = "rad", .doc = "Its heading spread", .choices = {}, .range = kNonNegative});
  v.require(o.local_window >= o.local_min_pairs, "local_window", ">= local_min_pairs");
  v.group("submap", "The plan filter's pose checked against the last scans' submap",
          [&] { visit(v, o.submap); });
}

void visit(OptionVisitor& v, ScaleSearchOptions& o) {
  v.group("range",
          "Scales (world metres per plan metre) searched when the plan's scale is not given",
          [&] { visit(v, o.range); });
  v.field(
      "initial_sigma_share", o.initial_sigma_share,
      {.unit = "",
       .doc = "Spread of the scales at the search start, as a share of the range (no registration)",
       .choices = {},
       .range = kPositive});
  enum_field(v, "model", o.model,
             {{"likelihood_field", ObservationModelKind::likelihood_field},
              {"beam", ObservationModelKind::beam}},
             "The plan filter's model during the search");
  v.group("observation", "Beams per scan of the search", [&] { visit(v, o.observation); });
  v.field(
      "walk", o.walk,
      {.unit = "",
       .doc = "Random walk of the scale during the search, per square root of a metre travelled",
       .choices = {},
       .range = kNonNegative});
  v.field("scans", o.scans,
          {.unit = "",
           .doc = "Scans of the search after the plan filter started",
           .choices = {},
           .range = at_least(1)});
  v.field("profile_range", o.profile_range,
          {.unit = "",
           .doc = "Profile the searched scale over 1 +- this (share)",
           .choices = {},
           .range = kOpenShare});
  v.field("profile_steps", o.profile_steps,
          {.unit = "", .doc = "Profile steps each way", .choices = {}, .range = between(1, 1e4)});
  v.field("profile_scans", o.profile_scans,
          {.unit = "scans", .doc = "Scans profiled at most", .choices = {}, .range = at_least(1)});
  v.field("maps_scans", o.maps_scans,
          {.unit = "scans",
           .doc = "With the maps aligned first: the scale by dead reckoning up to this many of the "
                  "gridmap filter's sure scans on the plan from where the maps put them",
           .choices = {},
           .range = at_least(1)});
  v.field("maps_segment_scans", o.maps_segment_scans,
          {.unit = "scans",
           .doc = "... in segments of this many, each from where the maps put its first scan",
           .choices = {},
           .range = at_least(2)});
  v.field("maps_fit_share", o.maps_fit_share,
          {.unit = "",
           .doc = "... the vertex of a parabola through the scales counting at least this share "
                  "of the way from the fewest endpoints on walls to the most",
           .choices = {},
           .range = between(0, 0.99)});
  v.field("maps_sigmas", o.maps_sigmas,
          {.unit = "",
           .doc = "Over the maps' scale 1 +- this many spreads",
           .choices = {},
           .range = kNonNegative});
  v.field("maps_min_range", o.maps_min_range,
          {.unit = "", .doc = "... at least this share", .choices = {}, .range = kOpenShare});
  v.field("maps_max_range", o.maps_max_range,
          {.unit = "", .doc = "... at most this share", .choices = {}, .range = kOpenShare});
  v.require(o.maps_min_range <= o.maps_max_range, "maps_min_range", "at most maps_max_range");
}

void visit(OptionVisitor& v, MapCorrelationOptions& o) {
  v.field("cell", o.cell,
          {.unit = "m",
           .doc = "Cell of the coarse images",
           .choices = {},
           .range = between(0.01, 100)});
  v.field("closeness", o.closeness,
          {.unit = "m",
           .doc = "Sigma of a plan wall's closeness at that level",
           .choices = {},
           .range = kPositive});
  v.field("scale_step", o.scale_step,
          {.unit = "",
           .doc = "Relative step of the scale lattice",
           .choices = {},
           .range = between(0.001, 1)});
  v.field("peaks", o.peaks,
          {.unit = "",
           .doc = "Candidates kept over all turns and scales",
           .choices = {},
           .range = between(1, 1e4)});
}

void visit(OptionVisitor& v, MapRegistrationOptions& o) {
  v.field("min_scale", o.min_scale,
          {.unit = "",
           .doc = "Plan metres per world metre searched, from",
           .choices = {},
           .range = kPositive});
  v.field("max_scale", o.max_scale, {.unit = "", .doc = "to", .choices = {}, .range = kPositive});
  v.field("scale_step", o.scale_step,
          {.unit = "",
           .doc = "Relative step of the profile search's scales",
           .choices = {},
           .range = between(0.001, 1)});
  v.field(
      "profile_bin", o.profile_bin,
      {.unit = "m", .doc = "Bin of the wall profiles", .choices = {}, .range = between(0.01, 100)});
  v.field("candidates", o.candidates,
          {.unit = "",
           .doc = "Profile candidates scored in 2D and refined",
           .choices = {},
           .range = between(1, 1e4)});
  v.field("max_points", o.max_points,
          {.unit = "",
           .doc = "Wall points of each map scored in 2D",
           .choices = {},
           .range = between(10, 1e7)});
  v.field("final_points", o.final_points,
          {.unit = "",
           .doc = "Wall points of each map in the best candidate's last refinement (0: none)",
           .choices = {},
           .range = between(0, 1e7)});
  v.field("sigma", o.sigma,
          {.unit = "m",
           .doc = "How near a wall a point must lie to count",
           .choices = {},
           .range = kPositive});
  v.field("free_violation_distance", o.free_violation_distance,
          {.unit = "m",
           .doc = "A plan wall this far inside the gridmap's free space counts against",
           .choices = {},
           .range = kNonNegative});
  v.field("correlation_below", o.correlation_below,
          {.unit = "",
           .doc = "Below this best profile score, a 2-D correlation search adds candidates "
                  "(> 1: always, < -1: never)",
           .choices = {},
           .range = any_number()});
  v.group("correlation", "That 2-D correlation search", [&] { visit(v, o.correlation); });
  v.field("alternatives", o.alternatives,
          {.unit = "",
           .doc = "Distinct other candidates kept (the maps-only alignment bends them too)",
           .choices = {},
           .range = between(1, 100)});
  v.require(o.max_scale >= o.min_scale, "max_scale", ">= min_scale");
}

void visit(OptionVisitor& v, PlanLocationOptions& o) {
  v.field("visible_walls_only", o.visible_walls_only,
          {.unit = "",
           .doc = "Localize on the plan's walls as a robot inside sees them (far faces dropped)",
           .choices = {}});
  v.group("visible", "How the visible walls are found", [&] { visit(v, o.visible); });
  v.group("submap", "Without a start", [&] { visit(v, o.submap); });
  v.group("registration", "The submap's global search", [&] { visit(v, o.registration); });
  v.group("registration_likelihood", "The plan's likelihood field for the registration",
          [&] { visit(v, o.registration_likelihood); });
  v.field("register_maps", o.register_maps,
          {.unit = "",
           .doc = "Without a scale: register the gridmap on the plan directly first (0.25-4x)",
           .choices = {}});
  v.group("map_registration", "That registration", [&] { visit(v, o.map_registration); });
  v.field("map_min_score", o.map_min_score,
          {.unit = "",
           .doc = "Score the map registration needs to set the scale range",
           .choices = {},
           .range = kScore});
  v.field("map_scale_margin", o.map_scale_margin,
          {.unit = "",
           .doc = "Scale range around its scale, 1 +- this (share)",
           .choices = {},
           .range = OptionRange{.min = 0.0, .max = 1.0, .min_open = false}});
  v.field("map_clear_margin", o.map_clear_margin,
          {.unit = "",
           .doc = "Score margin over the runner-up for its scale and pose to be used as they are",
           .choices = {},
           .range = kNonNegative});
  v.field("min_plan_match", o.min_plan_match,
          {.unit = "",
           .doc = "Score the maps need under the pairs' similarity, else the plan is another "
                  "building's and the run fails",
           .choices = {},
           .range = kScore});
  v.field("max_plan_walls_in_free_space", o.max_plan_walls_in_free_space,
          {.unit = "",
           .doc = "Share of the plan's walls in the robot's free space under the pairs' "
                  "similarity beyond which the run fails",
           .choices = {},
           .range = kShare});
  v.field("start_from_maps", o.start_from_maps,
          {.unit = "",
           .doc = "Start the run from the maps' alignment when it was accepted (its bent map "
                  "places the plan filter, its scale seeds the search)",
           .choices = {}});
  v.field("maps_start_sigma", o.maps_start_sigma,
          {.unit = "m",
           .doc = "Plan filter's first spread around the pose the maps give (world metres)",
           .choices = {},
           .range = kNonNegative});
  v.field("maps_start_heading_sigma", o.maps_start_heading_sigma,
          {.unit = "rad", .doc = "Its heading spread", .choices = {}, .range = kNonNegative});
  v.field("maps_min_scale_share", o.maps_min_scale_share,
          {.unit = "",
           .doc = "The scale search's first spread around the maps' scale, at least this share",
           .choices = {},
           .range = kOpenShare});
  v.field("given_start_sigma", o.given_start_sigma,
          {.unit = "m",
           .doc = "Plan filter's first spread around a given start",
           .choices = {},
           .range = kNonNegative});
  v.field("given_start_heading_sigma", o.given_start_heading_sigma,
          {.unit = "rad", .doc = "Its heading spread", .choices = {}, .range = kNonNegative});
  v.field("registered_start_sigma", o.registered_start_sigma,
          {.unit = "m",
           .doc = "Plan filter's first spread around the registered start",
           .choices = {},
           .range = kNonNegative});
  v.field("registered_start_heading_sigma", o.registered_start_heading_sigma,
          {.unit = "rad", .doc = "Its heading spread", .choices = {}, .range = kNonNegative});
}

void visit(OptionVisitor& v, GridmapLocalizationOptions& o) {
  v.field(
      "max_global_scans", o.max_global_scans,
      {.unit = "",
       .doc = "Global localization on the gridmap fails when not converged after this many scans",
       .choices = {},
       .range = at_least(1)});
  v.field("restart_near_scans", o.restart_near_scans,
          {.unit = "",
           .doc = "A diverged gridmap filter looks around its last converged pose this many scans "
                  "before a global restart (0: global at once)",
           .choices = {},
           .range = at_least(0)});
  v.field("restart_sigma", o.restart_sigma,
          {.unit = "m",
           .doc = "That cloud's spread (+10% per metre travelled)",
           .choices = {},
           .range = kNonNegative});
  v.field("restart_heading_sigma", o.restart_heading_sigma,
          {.unit = "rad", .doc = "and its heading spread", .choices = {}, .range = kNonNegative});
}

void visit(OptionVisitor& v, WallFieldOptions& o) {
  v.field("max_distance", o.max_distance,
          {.unit = "m",
           .doc = "Cells farther than this from every wall have no nearest wall point",
           .choices = {},
           .range = kPositive});
  v.field("normal_radius", o.normal_radius,
          {.unit = "cells",
           .doc = "A wall cell's normal comes from the occupied cells within this radius (>= 1)",
           .choices = {},
           .range = between(1, 100)});
  v.field("max_flatness", o.max_flatness,
          {.unit = "",
           .doc = "A wall cell gets a normal when its neighbours' scatter is this flat (0 to 1)",
           .choices = {},
           .range = kOpenShare});
}

void visit(OptionVisitor& v, BeamModelOptions& o) {
  v.field("weight_hit", o.weight_hit,
          {.unit = "",
           .doc = "alpha: weight of hits of the expected wall (eq. 3.47)",
           .choices = {},
           .range = kNonNegative});
  v.field("weight_unexpected", o.weight_unexpected,
          {.unit = "",
           .doc = "beta: weight of beams stopped short by what the map lacks",
           .choices = {},
           .range = kNonNegative});
  v.field("weight_random", o.weight_random,
          {.unit = "",
           .doc = "gamma: weight of random readings (> 0)",
           .choices = {},
           .range = kPositive});
  v.field("weight_max", o.weight_max,
          {.unit = "",
           .doc = "delta: weight of max-range readings",
           .choices = {},
           .range = kNonNegative});
  v.field("sigma_hit", o.sigma_hit,
          {.unit = "m",
           .doc = "Standard deviation of a hit about the expected range (eq. 3.43)",
           .choices = {},
           .range = kPositive});
  v.field("lambda_unexpected", o.lambda_unexpected,
          {.unit = "1/m",
           .doc = "Rate of the exponential of unexpected short readings (eq. 3.46)",
           .choices = {},
           .range = kPositive});
  v.field("max_range", o.max_range,
          {.unit = "m",
           .doc = "z_max of eq. 3.44-3.45 (0: each scan's own)",
           .choices = {},
           .range = kNonNegative});
  v.field("max_window", o.max_window,
          {.unit = "m",
           .doc = "Width of the max-range part below the max range (eq. 3.45)",
           .choices = {},
           .range = kPositive});
  v.field("beam_weight", o.beam_weight,
          {.unit = "",
           .doc = "Temperature: the scan's log-likelihood times this",
           .choices = {},
           .range = kPositive});
  v.field("unknown_is_occupied", o.unknown_is_occupied,
          {.unit = "",
           .doc = "Whether unknown cells stop the ray casting (GridRayCasterOptions)",
           .choices = {}});
}

void visit(OptionVisitor& v, MapFilterOptions& o) {
  v.group("filter", "The particle filter", [&] { visit(v, o.filter); });
  enum_field(v, "model", o.model,
             {{"likelihood_field", ObservationModelKind::likelihood_field},
              {"beam", ObservationModelKind::beam}},
             "Its observation model");
  v.group("likelihood", "The likelihood field (always built", [&] { visit(v, o.likelihood); });
  v.group("observation", "Beams per scan of the filter", [&] { visit(v, o.observation); });
  v.group("runner", "How the filter is fed", [&] { visit(v, o.runner); });
}

void visit(OptionVisitor& v, ModelComparisonOptions& o) {
  v.field("models", o.models, {.unit = "", .doc = "The models fitted and judged", .choices = {}});
  v.group("mapping", "Options of every model (`model` is set per model)",
          [&] { visit(v, o.mapping); });
  v.field("cv_folds", o.cv_folds,
          {.unit = "",
           .doc = "k of each model's k-fold cross-validation (0: none)",
           .choices = {},
           .range = between(0, 1000)});
  v.field("back_and_forth_rounds", o.back_and_forth_rounds,
          {.unit = "",
           .doc = "Round trips per point of the back-and-forth test (thesis 6.5)",
           .choices = {},
           .range = between(0, 1e6)});
  v.field("back_and_forth_points", o.back_and_forth_points,
          {.unit = "", .doc = "Domain points followed", .choices = {}, .range = between(0, 1e7)});
  v.require(o.cv_folds != 1, "cv_folds", "0 (no cross-validation) or at least 2");
  v.field("ideal_pairs", o.ideal_pairs,
          {.unit = "",
           .doc = "With a truth, also fit each model on ideal pairs (the truth at the pairs' plan "
                  "points) and judge it: the pairs' own loss",
           .choices = {}});
}

void visit(OptionVisitor& v, PairSourceOptions& o) {
  v.field("coverage_radius", o.coverage_radius,
          {.unit = "m",
           .doc = "A gridmap wall point this near a pair's grid point is covered by the pairs",
           .choices = {},
           .range = kNonNegative});
  v.field("min_coverage", o.min_coverage,
          {.unit = "",
           .doc = "Share of the gridmap's walls the run's pairs must cover",
           .choices = {},
           .range = kShare});
  v.field("min_pair_scans", o.min_pair_scans,
          {.unit = "scans",
           .doc = "Scans the run's pairs must come from...",
           .choices = {},
           .range = kNonNegative});
  v.field("min_pair_scan_share", o.min_pair_scan_share,
          {.unit = "",
           .doc = "... or this share of the log's scans when fewer",
           .choices = {},
           .range = kShare});
  v.field("min_converged_share", o.min_converged_share,
          {.unit = "",
           .doc = "... and both filters converged on at least this share of the scans",
           .choices = {},
           .range = kShare});
  v.field("disagreement_sigmas", o.disagreement_sigmas,
          {.unit = "",
           .doc = "The run's pairs agree with the maps' bent map when their median distance "
                  "through it is within this many of their stated uncertainty (the pairs' noise "
                  "and the bent map's scale spread over the pairs' extent)",
           .choices = {},
           .range = kNonNegative});
  v.field("min_disagreement_tolerance", o.min_disagreement_tolerance,
          {.unit = "m", .doc = "... at least this", .choices = {}, .range = kNonNegative});
  v.field("scale_sigmas", o.scale_sigmas,
          {.unit = "",
           .doc = "... and their scales differ by at most this many of the maps' scale spread",
           .choices = {},
           .range = kNonNegative});
  v.field("min_scale_tolerance", o.min_scale_tolerance,
          {.unit = "",
           .doc = "... or this share of the scale, when more",
           .choices = {},
           .range = kNonNegative});
  v.field("fill_radius", o.fill_radius,
          {.unit = "m",
           .doc = "When the run's pairs are used and agree with the maps', the maps' pairs "
                  "farther than this from every run pair are added (0: none)",
           .choices = {},
           .range = kNonNegative});
  v.field("shared_bias", o.shared_bias,
          {.unit = "",
           .doc = "Every model's std_m carries a bias all pairs share: where the run's pairs and "
                  "the maps' alignment agree, their distance averaged per place; with the maps' "
                  "pairs alone, their scale spread over the pairs' extent; and the outer walls' "
                  "faces neither took out",
           .choices = {}});
  v.field("bias_cell", o.bias_cell,
          {.unit = "m",
           .doc = "... that distance averaged, as vectors, over cells this wide",
           .choices = {},
           .range = above_to(0.0, 1e3)});
  v.field("run_match_margin", o.run_match_margin,
          {.unit = "",
           .doc = "When they disagree, the run's pairs are kept only when the plan-match check "
                  "scores them higher than the maps' by more than this (a tie goes to the maps; "
                  "negative: the run's are kept up to that much below)",
           .choices = {},
           .range = kScore});
}

void visit(OptionVisitor& v, DualLocalizerOptions& o) {
  v.group("plan", "The filter on the floorplan", [&] { visit(v, o.plan); });
  v.group("grid", "The filter on the gridmap", [&] { visit(v, o.grid); });
  v.group("beam", "The beam model of the filters that choose it", [&] { visit(v, o.beam); });
  v.group("walls", "The scan matchers' wall lookup", [&] { visit(v, o.walls); });
  v.field("plan_beam_consistency", o.plan_beam_consistency,
          {.unit = "",
           .doc = "Match scans onto the plan by the beams that reach its first wall",
           .choices = {}});
  enum_field(v, "plan_wall_line", o.plan_wall_line,
             {{"auto", PlanWallLine::automatic},
              {"cell_centres", PlanWallLine::cell_centres},
              {"ink_edges", PlanWallLine::ink_edges}},
             "Where scans meet a raster plan's walls: its ink cells' centres (a plan traced over "
             "a gridmap), its ink's edges (walls filled in as built or thicker than drawn), or "
             "auto (the edges where the maps' faces lie ink_edge_min_offset off the strokes)");
  v.field("ink_edge_min_offset", o.ink_edge_min_offset,
          {.unit = "m",
           .doc = "With plan_wall_line auto: the partitions' faces this far off their strokes "
                  "(the maps' faces fit, world metres) mean the ink's edges",
           .choices = {},
           .range = kNonNegative});
  v.field("refine_poses", o.refine_poses,
          {.unit = "",
           .doc = "Pairs only from scans whose scan match succeeded on both maps",
           .choices = {}});
  v.field("guide_plan_by_gridmap", o.guide_plan_by_gridmap,
          {.unit = "",
           .doc = "The plan filter moves by the converged gridmap filter's motion, not the "
                  "odometry's",
           .choices = {}});
  v.group("gridmap_localization", "Step 1", [&] { visit(v, o.gridmap_localization); });
  v.group("plan_location", "Step 2", [&] { visit(v, o.plan_location); });
  v.group("scale_search", "Step 3", [&] { visit(v, o.scale_search); });
  v.group("dual_check", "Step 4", [&] { visit(v, o.dual_check); });
  v.group("scale_refit", "Step 5", [&] { visit(v, o.scale_refit); });
  v.group("pairs", "How endpoints become pairs", [&] { visit(v, o.pairs); });
  v.group("pose_pull",
          "The plan poses' pull along the robot's heading, measured from revisits and taken "
          "out of the pairs",
          [&] { visit(v, o.pose_pull); });
  v.group("outlier_scans",
          "Scans whose pairs disagree with the other scans' at the same walls are dropped",
          [&] { visit(v, o.outlier_scans); });
  v.field(
      "threads", o.threads,
      {.unit = "", .doc = "Threads of the observation models", .choices = {}, .range = kThreads});
  v.field("seed", o.seed,
          {.unit = "",
           .doc = "Randomness of both filters (see SeedStream)",
           .choices = {},
           .range = kSeed});
}

void visit(OptionVisitor& v, WallSlideOptions& o) {
  v.field("iterations", o.iterations,
          {.unit = "",
           .doc = "Rounds of fit-and-slide (0: the pairs as the filters made them)",
           .choices = {},
           .range = between(0, 100)});
  v.field("radius", o.radius,
          {.unit = "m",
           .doc = "A pair's wall direction comes from the gridmap's occupied cells this near",
           .choices = {},
           .range = kPositive});
  v.field("max_flatness", o.max_flatness,
          {.unit = "",
           .doc = "Scatter across a wall over along it at most this for a straight wall",
           .choices = {},
           .range = kOpenShare});
  v.field("smoother", o.smoother,
          {.unit = "", .doc = "The model whose prediction a pair slides to", .choices = {}});
  v.field("min_along_ratio", o.min_along_ratio,
          {.unit = "",
           .doc = "Pairs slide only when their noise between visits is this many times larger "
                  "along their walls than across",
           .choices = {},
           .range = at_least(1.0)});
}

void visit(OptionVisitor& v, WallFaceOptions& o) {
  v.field("enabled", o.enabled,
          {.unit = "",
           .doc = "Refine the maps' registration with the offsets of the walls' faces off their "
                  "strokes (outer walls and the rest), and bend onto the faces",
           .choices = {}});
  v.field("seal_radius", o.seal_radius,
          {.unit = "m",
           .doc = "Gaps up to twice this in the drawing's outer walls are closed when telling "
                  "the outside from the inside",
           .choices = {},
           .range = between(0.01, 100)});
  v.field("max_depth", o.max_depth,
          {.unit = "m",
           .doc = "The outside is looked for this deep behind a wall surface",
           .choices = {},
           .range = between(0.01, 10)});
  v.field("radius", o.radius,
          {.unit = "m",
           .doc = "A gridmap wall point is matched to a plan wall this near",
           .choices = {},
           .range = between(0.01, 10)});
  v.field("huber", o.huber,
          {.unit = "m",
           .doc = "Residuals beyond this are down-weighted",
           .choices = {},
           .range = between(0.001, 10)});
  v.field("iterations", o.iterations,
          {.unit = "",
           .doc = "Rounds of matching and refitting",
           .choices = {},
           .range = between(1, 100)});
  v.field("min_points", o.min_points,
          {.unit = "",
           .doc = "Matched points on outer walls, and on the others, the fit needs",
           .choices = {},
           .range = between(1, 1e9)});
  v.field("max_offset", o.max_offset,
          {.unit = "m",
           .doc = "An outer faces' offset beyond this (or below a quarter of it negated), or a "
                  "partition offset beyond half of it, is not trusted",
           .choices = {},
           .range = between(0.001, 10)});
  v.field("max_scale_change", o.max_scale_change,
          {.unit = "",
           .doc = "A refined scale farther off the registration's than this share is not trusted",
           .choices = {},
           .range = kOpenShare});
  v.field("min_offset_difference", o.min_offset_difference,
          {.unit = "m",
           .doc = "The outer walls' faces must lie this much farther off their strokes than the "
                  "partitions' for the fit to be used",
           .choices = {},
           .range = between(-10, 10)});
  v.field("localize_on_faces", o.localize_on_faces,
          {.unit = "",
           .doc = "The run localizes on the plan with its strokes grown to the faces found "
                  "(raster plans)",
           .choices = {}});
}

void visit(OptionVisitor& v, MapAlignmentOptions& o) {
  v.field("first_spacing", o.first_spacing,
          {.unit = "m",
           .doc = "The displacement lattice's node spacing, first stage",
           .choices = {},
           .range = between(0.01, 1e3)});
  v.field("last_spacing", o.last_spacing,
          {.unit = "m",
           .doc = "and in the finest stage (halved between)",
           .choices = {},
           .range = between(0.01, 1e3)});
  v.field("first_radius", o.first_radius,
          {.unit = "m",
           .doc = "A gridmap wall point matches a plan wall this near, first stage",
           .choices = {},
           .range = kPositive});
  v.field("last_radius", o.last_radius,
          {.unit = "m", .doc = "and in the finest stage", .choices = {}, .range = kPositive});
  v.field("rounds", o.rounds,
          {.unit = "",
           .doc = "Correspondence rounds per stage",
           .choices = {},
           .range = between(1, 100)});
  v.field(
      "stiffness", o.stiffness,
      {.unit = "", .doc = "The lattice's membrane weight", .choices = {}, .range = kNonNegative});
  v.field("point_spacing", o.point_spacing,
          {.unit = "m",
           .doc = "Between the gridmap wall points used",
           .choices = {},
           .range = between(0.001, 100)});
  v.field("max_normal_angle", o.max_normal_angle,
          {.unit = "deg",
           .doc = "Matched walls' directions differ at most this",
           .choices = {},
           .range = above_to(0.0, 90)});
  v.field("pair_radius", o.pair_radius,
          {.unit = "m",
           .doc = "Final matches this near their plan wall become the pairs",
           .choices = {},
           .range = kPositive});
  v.field("min_fitness", o.min_fitness,
          {.unit = "",
           .doc = "Accepted when on_walls - in_free_space after the refinement is at least this",
           .choices = {},
           .range = any_number()});
  v.field("min_on_walls", o.min_on_walls,
          {.unit = "",
           .doc = "Accepted when at least this share of the gridmap's walls lie on the plan's",
           .choices = {},
           .range = kShare});
  v.field("max_ambiguity", o.max_ambiguity,
          {.unit = "",
           .doc = "Not accepted when the best other place, bent too, fits this share of it",
           .choices = {},
           .range = kPositive});
  v.field("correlation_below", o.correlation_below,
          {.unit = "",
           .doc = "The registration's 2-D correlation search below this profile score (> 1: "
                  "always)",
           .choices = {},
           .range = any_number()});
  v.group("faces", "Where the laser meets the drawn walls: the registration refined with them",
          [&] { visit(v, o.faces); });
  v.require(o.last_spacing <= o.first_spacing, "last_spacing", "<= first_spacing");
}

void visit(OptionVisitor& v, AlignmentOptions& o) {
  v.group("localization", "How pairs are made", [&] { visit(v, o.localization); });
  v.group("models", "Which models, cross-validation, back-and-forth", [&] { visit(v, o.models); });
  v.group("wall_slide", "The pairs slid along their gridmap walls before the models are fitted",
          [&] { visit(v, o.wall_slide); });
  enum_field(v, "pairs_from", o.pairs_from,
             {{"run", PairSource::run}, {"maps", PairSource::maps}, {"both", PairSource::both}},
             "Where the pairs come from: the robot's run, the two maps alone, or both (a "
             "dataset without a log: the maps)");
  v.group("maps_only",
          "The maps aligned (first, always; the pairs with no log, or --pairs-from maps|both): "
          "registration, then a non-rigid refinement",
          [&] { visit(v, o.maps_only); });
  v.group("sources",
          "The run's pairs judged on their own and against the maps' alignment, and which are "
          "used",
          [&] { visit(v, o.sources); });
  v.field("near_pairs", o.near_pairs,
          {.unit = "m",
           .doc = "Wall distances are also summarized over the plan wall points this close to a "
                  "pair (where the models have data)",
           .choices = {},
           .range = kNonNegative});
  v.field("wall_distance_cap", o.wall_distance_cap,
          {.unit = "m",
           .doc = "The gridmap's distance field for wall distances is capped here",
           .choices = {},
           .range = kPositive});
  v.field("domain_spacing", o.domain_spacing,
          {.unit = "m",
           .doc = "Between the plan wall samples of the evaluation domain",
           .choices = {},
           .range = between(0.001, 100)});
}

void visit(OptionVisitor& v, io::DatasetLimits& o) {
  v.field("memory_gb", o.memory_gb,
          {.unit = "",
           .doc = "GiB the maps may take to localize in (0: half of this machine's memory)",
           .choices = {},
           .range = OptionRange{.min = 0.0, .max = 1e6, .min_open = false}});
  v.field("crop_above_cells", o.crop_above_cells,
          {.unit = "cells",
           .doc = "Maps larger than this are cropped to their known cells and crop_margin around",
           .choices = {},
           .range = at_least(1)});
  v.field("crop_margin", o.crop_margin,
          {.unit = "m",
           .doc = "Margin kept around a cropped map's known area",
           .choices = {},
           .range = between(0, 1e3)});
}

void visit(OptionVisitor& v, io::PlanRasterOptions& o) {
  v.field("resolution", o.resolution,
          {.unit = "m",
           .doc = "Cell size of a rasterized DXF plan",
           .choices = {},
           .range = between(0.001, 10)});
  v.field("wall_thickness", o.wall_thickness,
          {.unit = "m",
           .doc = "0 draws each drawn line one cell wide",
           .choices = {},
           .range = between(0, 10)});
  v.field(
      "margin", o.margin,
      {.unit = "m", .doc = "Free border around the plan", .choices = {}, .range = between(0, 1e3)});
}

void visit(OptionVisitor& v, PlanUnitFitOptions& o) {
  v.field("scale_margin", o.scale_margin,
          {.unit = "",
           .doc = "Each unit is tried at the expected floorplan_scale times or divided by this",
           .choices = {},
           .range = above_to(1.0, 100)});
  v.field("min_score", o.min_score,
          {.unit = "",
           .doc = "Registration score a unit needs to be chosen by the run",
           .choices = {},
           .range = kScore});
  v.field("clear_margin", o.clear_margin,
          {.unit = "",
           .doc = "How much better than the drawing's unit another must fit to overrule it",
           .choices = {},
           .range = between(0, 2)});
  v.field("max_cells", o.max_cells,
          {.unit = "cells",
           .doc = "A unit's plan is drawn coarser beyond this",
           .choices = {},
           .range = between(10000, 1e9)});
  v.group("registration", "The gridmap registered on the plan under each unit",
          [&] { visit(v, o.registration); });
}

void visit(OptionVisitor& v, JobOptions& o) {
  v.group("raster", "How a DXF plan becomes a grid", [&] { visit(v, o.raster); });
  v.group("limits", "What loading a dataset may cost", [&] { visit(v, o.limits); });
  v.group("units", "How the run decides a DXF's units when the drawing leaves several plausible",
          [&] { visit(v, o.units); });
  v.group("align", "The main job: localization, models, evaluation", [&] { visit(v, o.align); });
}

namespace io {

OptionTree job_option_tree(JobOptions& options) {
  return [&options](OptionVisitor& v) { visit(v, options); };
}

}  // namespace io

}  // namespace floorgrid
