#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace floorgrid {

/// Pairs dealt into the folds of a cross-validation.
struct Folds {
  std::vector<std::size_t> fold_of;   ///< per pair, its fold in [0, count)
  std::size_t count = 0;              ///< folds (fewer than asked when there are fewer blocks)
  double block_size = 0.0;            ///< metres, side of the square blocks (0: random folds)
  std::vector<std::size_t> block_of;  ///< per pair, its block (blocked folds; empty otherwise)
  std::size_t blocks = 0;             ///< non-empty blocks (blocked folds)
  /// Every pair once, in the order training and test sets list them (random folds: the
  /// shuffled order, as k-fold always dealt them; blocked folds: the pairs' own order).
  std::vector<std::size_t> order;

  /// The pairs of `fold` (test) and of every other fold (train), in `order` (index order when
  /// it is empty): some fits depend on the order of their pairs (ct's clustering).
  void split(std::size_t fold, std::vector<Eigen::Index>& train,
             std::vector<Eigen::Index>& test) const;
};

/// Random folds, the classic k-fold: the pairs shuffled by `seed`, then dealt round robin into
/// min(folds, n) folds. Dense laser pairs have near-copies in every fold, so this measures
/// little more than the noise an interpolator reproduces.
Folds random_folds(std::size_t n, std::size_t folds, std::uint64_t seed);

/// Spatially blocked folds: `points` (metres) binned into square blocks of `block_size` metres
/// aligned on the points' lower-left bound; the blocks, in an order shuffled by `seed`, each go
/// whole to the fold holding the fewest points so far, into min(folds, blocks) folds. A held-out
/// pair's block is never in training, so what is measured is the error away from the pairs.
Folds blocked_folds(const Eigen::Matrix2Xd& points, std::size_t folds, double block_size,
                    std::uint64_t seed);

/// Folds of runs: the n pairs, in their order, cut into folds x runs_per_fold stretches of
/// (nearly) equal length, stretch s going to fold s mod folds (min(folds, n) folds). Pairs in
/// scan order share their errors along a stretch of the run (the filters' pose errors); held
/// out whole, each stretch is predicted from the other passes and stretches only.
Folds run_folds(std::size_t n, std::size_t folds, std::size_t runs_per_fold);

/// Stretches per fold of run_folds as cross-validation deals them.
inline constexpr std::size_t kRunsPerFold = 3;

/// Stretches of the run the pairs are cut into where pairs of one stretch may share an error
/// and pairs of different stretches count as independent: the standard error of a paired
/// score difference, and the pairs' own noise (pair_noise).
inline constexpr std::size_t kRunStretches = 40;

/// The stretch pair i of n falls in (0 .. stretches - 1), of `stretches` stretches of (nearly)
/// equal length in the pairs' order.
inline std::size_t run_stretch(std::size_t i, std::size_t n, std::size_t stretches) {
  return i * stretches / n;
}

/// The block side blocked_folds uses when none is given: kLargestAutoBlock metres, shrunk (by
/// 0.8 each step) until the points fill at least kAutoBlocksPerFold blocks per fold, but never
/// below twice the median distance between neighbouring points (density), so a block always
/// holds a point's near-copies.
double choose_block_size(const Eigen::Matrix2Xd& points, std::size_t folds);

/// Largest block side choose_block_size returns, metres: a few metres, the scale of a room
/// or a stretch of corridor, beyond the reach of a scan's near-copies.
inline constexpr double kLargestAutoBlock = 4.0;
/// Pairs from which a model tunes itself (tps's smoothing, the GP's kernel scale) on blocked
/// folds: fewer are sparse, hand-picked pairs without near-copies, where a block holds about
/// one pair anyway and the classic folds were measured better (Halmstad leave-one-out).
inline constexpr std::size_t kBlockedTuningMinPairs = 100;
/// Non-empty blocks per fold choose_block_size asks for at least.
inline constexpr std::size_t kAutoBlocksPerFold = 4;

}  // namespace floorgrid
