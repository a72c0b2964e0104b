#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "floorgrid/mapping/gp_kernel.hpp"
#include "floorgrid/mapping/rprop.hpp"

namespace floorgrid {

/// How a GP's hyperparameters are tuned: RPROP on the log-hyperparameters maximizing the log
/// marginal likelihood (thesis 3.3.1-3.3.2; eq. 3.29's training error is degenerate, see the
/// SPEC's pitfalls) on a spatially spread subsample, within box bounds that keep K well
/// conditioned and the length scales meaningful.
struct GpTuningOptions {
  /// tune on at most this many points, a farthest-point subsample of the training points
  /// (the N^3 cost of every RPROP iteration); >= 3
  int max_points = 400;
  /// metres: the smallest noise std allowed (sn^2 on K's diagonal bounds its condition
  /// number); > 0
  double min_noise_std = 1e-4;
  /// the smallest length scale, as a multiple of the tuning points' median nearest-neighbour
  /// distance (below it the subsample cannot see the length scale); > 0
  double min_length_scale_factor = 1.0;
  /// the smallest length scale also as a multiple of the training points' extent (0: no such
  /// floor); >= 0 and <= max_length_scale_factor
  double min_length_scale_extent = 0.0;
  /// the largest length scale, as a multiple of the training points' extent (the longer side
  /// of their bounding box; beyond it the kernel is flat over the data); >= min
  double max_length_scale_factor = 10.0;
  /// the largest signal std, as a multiple of the outputs' RMS about their mean (enough for a
  /// near-linear trend at the largest length scale, about 35 times the RMS); > 0
  double max_signal_std_factor = 100.0;
  /// the optimizer; its bounds (lower, upper) are set from the ones above and must be empty
  RpropOptions rprop;
};

/// Checks `options`; throws InputError naming the field as `<prefix>.<field>`
/// (`gaussian_process.tuning.max_points`, `gaussian_process.tuning.rprop.increase`, ...).
void validate_gp_tuning_options(const GpTuningOptions& options, const std::string& prefix);

/// Box bounds on the hyperparameters (metres).
struct GpHyperparameterBounds {
  GpHyperparameters lower;  ///< smallest length scales, signal std and noise std
  GpHyperparameters upper;  ///< largest ones
};

/// What tune_gp_hyperparameters did.
struct GpTuningResult {
  GpHyperparameters hyperparameters;     ///< the tuned ones (the best RPROP evaluated)
  GpHyperparameters initial;             ///< RPROP's start: the best of a small grid of guesses
  GpHyperparameterBounds bounds;         ///< the box RPROP searched
  Eigen::Index tuning_points = 0;        ///< size of the subsample tuned on
  double log_marginal_likelihood = 0.0;  ///< on the subsample, at `hyperparameters`
  RpropResult rprop;                     ///< iterations, history (of -log likelihood), ...
  /// names of the hyperparameters that ended at a bound (`length_scale_x`, `length_scale_y`,
  /// `signal_std`, `noise_std`, each with `@lower` or `@upper`)
  std::vector<std::string> at_bounds;
};

/// Indices of a spatially spread subsample of `count` points by farthest-point sampling: the
/// point nearest the centroid first, then repeatedly the point farthest from those chosen
/// (ties: the lowest index). All indices when count >= the number of points. Deterministic,
/// O(N count).
std::vector<Eigen::Index> gp_spread_subsample(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                              Eigen::Index count);

/// The bounds tune_gp_hyperparameters uses: length scales in
/// [min_length_scale_factor * s, max_length_scale_factor * E] (s: median nearest-neighbour
/// distance of `tuning_points`, at least 1e-6 E; E: the longer side of the bounding box of
/// `points`); signal std in [min_noise_std, max_signal_std_factor * max(r, min_noise_std)];
/// noise std in [min_noise_std, max(r, 10 min_noise_std)] (r: RMS of the centred outputs over
/// both coordinates: noise above the data's own spread explains nothing).
GpHyperparameterBounds gp_hyperparameter_bounds(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                                Eigen::Ref<const Eigen::Matrix2Xd> tuning_points,
                                                Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs,
                                                const GpTuningOptions& options);

/// Tunes the hyperparameters of a GP from `points` (2 x N, metres) to `centred_outputs` (2 x N,
/// their means removed): picks the subsample, sets the bounds, starts from the best of a grid
/// of guesses (length scales 0.05, 0.15, 0.5 and 1.5 times the extent, signal std r, noise std
/// 0.01 r and 0.1 r, all clipped into the bounds) and runs RPROP on
/// -log marginal likelihood. The points must be valid (finite, N >= 3, not all equal).
GpTuningResult tune_gp_hyperparameters(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                       Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs,
                                       const GpTuningOptions& options = {});

}  // namespace floorgrid
