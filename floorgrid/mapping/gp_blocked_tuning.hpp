#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "floorgrid/mapping/gp_kernel.hpp"

namespace floorgrid {

/// One candidate of refine_by_blocked_cv and its held-out error.
struct GpBlockedCandidate {
  double length_factor = 1.0;  ///< the length scales times this
  double noise_factor = 1.0;   ///< the noise std times this
  double error_m = 0.0;        ///< mean held-out |error|, metres (infinite: a fold failed)
};

/// What refine_by_blocked_cv chose.
struct GpBlockedTuning {
  GpHyperparameters hyperparameters;      ///< the candidate with the least held-out error
  std::vector<GpBlockedCandidate> table;  ///< every candidate, in the order tried
  double block_size = 0.0;                ///< metres, side of the blocks held out
  std::size_t folds = 0;                  ///< folds used
};

/// Length-scale factors refine_by_blocked_cv tries (1: the likelihood's own).
inline constexpr double kGpLengthFactors[] = {1.0, 2.0, 4.0, 8.0};
/// Noise-std factors refine_by_blocked_cv tries.
inline constexpr double kGpNoiseFactors[] = {1.0, 3.0, 10.0};

/// Dense laser pairs have near-copies whose errors are correlated along a scan and a wall: the
/// marginal likelihood, which assumes independent noise, then explains that noise with short
/// length scales and a small noise std, and the GP interpolates it. This re-chooses the scale
/// of `tuned` (length scales times kGpLengthFactors, noise std times kGpNoiseFactors, signal std
/// kept) by spatially blocked cross-validation: the GP from `points` (2 x N plan, metres) to
/// `outputs` (2 x N) fitted on all blocks but one fold's predicts that fold; blocks are squares
/// of `blocks_at` (2 x N, the pairs in the grid frame, metres; blocked_folds and
/// choose_block_size) dealt by `seed`. Ties keep the earlier candidate (the likelihood's first).
/// Use it on a subsample (the cost is 12 folds x candidates Cholesky factorizations).
GpBlockedTuning refine_by_blocked_cv(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                     Eigen::Ref<const Eigen::Matrix2Xd> outputs,
                                     const Eigen::Matrix2Xd& blocks_at,
                                     const GpHyperparameters& tuned, std::size_t folds,
                                     std::uint64_t seed);

}  // namespace floorgrid
