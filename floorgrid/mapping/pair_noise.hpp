#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/cross_validation_folds.hpp"

namespace floorgrid {

/// How the pairs' own noise is estimated (see pair_noise).
struct PairNoiseOptions {
  /// Grid metres (the plan's units scaled by the pairs' similarity): two pairs this close in
  /// the plan count as measuring the same place.
  double radius = 0.3;
  /// The pairs, in the order they were made, are cut into this many stretches (run_stretch);
  /// two pairs of one stretch may share a pose error, two of different stretches count as
  /// independent visits.
  std::size_t stretches = kRunStretches;
  /// Pairs whose neighbours are looked at, spread evenly over all (cost bound).
  std::size_t queries = 4000;
  /// Neighbours of another stretch per query pair, nearest first.
  std::size_t neighbours = 5;
  /// Differences needed at least: with fewer there is no estimate.
  std::size_t min_differences = 30;
};

/// The pairs' own noise: the mean squared length of a pair's error E|n|^2 (both axes), from
/// pairs of different visits that measure the same place. For two such pairs i, j, with A the
/// linear part of the pairs' least-squares similarity, d = (g_j - g_i) - A (p_j - p_i) holds the
/// two visits' independent errors and not the mapping: E|d|^2 = 2 E|n|^2. An error that every
/// visit to a place shares (a bias of the pairs there) cancels too: no pair-based estimate sees
/// it. Pairs of one stretch are not compared: a scan's pairs share its pose error.
struct PairNoise {
  double mean_square_m2 = 0.0;  ///< E|n|^2, m^2
  std::size_t differences = 0;  ///< pair differences it was estimated from
};

/// The estimate, or nullopt with fewer than options.min_differences differences (pairs that
/// never revisit a place, or too few). Deterministic.
std::optional<PairNoise> pair_noise(const ReferencePairs& pairs,
                                    const PairNoiseOptions& options = {});

/// One difference between two visits to one place: the query pair's column and d (grid metres,
/// see PairNoise).
using VisitDifference = std::function<void(Eigen::Index i, const Eigen::Vector2d& d)>;

/// Calls `visit` for every difference pair_noise uses (the same pairs, places and stretches);
/// false when the pairs are too few or degenerate to form any.
bool for_each_visit_difference(const ReferencePairs& pairs, const PairNoiseOptions& options,
                               const VisitDifference& visit);

/// The pairs' own noise split along and across a direction per pair (a unit vector, or zero
/// where there is none: such query pairs are skipped).
struct DirectionalPairNoise {
  double along_m2 = 0.0;        ///< E n_along^2, m^2 (one axis)
  double across_m2 = 0.0;       ///< E n_across^2, m^2 (one axis)
  std::size_t differences = 0;  ///< differences it was estimated from
};

/// pair_noise along and across `along` (one direction per pair, in the grid frame), or nullopt
/// with fewer than options.min_differences differences. Deterministic.
std::optional<DirectionalPairNoise> pair_noise_along(const ReferencePairs& pairs,
                                                     const std::vector<Eigen::Vector2d>& along,
                                                     const PairNoiseOptions& options = {});

}  // namespace floorgrid
