#pragma once

#include <cstddef>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid {

/// How scans whose pairs disagree with the other scans' at the same walls are found.
struct OutlierScanOptions {
  bool enabled = true;  ///< false keeps every scan
  /// Plan metres: pairs are compared within cells of this size.
  double cell = 1.0;
  /// Grid metres: a scan whose pairs lie farther than this (median over its pairs) from what
  /// the other scans' pairs in the same cells say is dropped.
  double max_deviation = 0.15;
  /// Other scans' pairs a cell needs for its consensus to count.
  std::size_t min_cell_pairs = 20;
  /// Pairs needed at all: fewer are too few to tell a consensus from an outlier.
  std::size_t min_pairs = 100;
  /// Metres: the RANSAC inlier distance of the similarity the residuals are taken from (wide:
  /// it only has to carry the bulk of the map; the residuals keep the bends).
  double similarity_inlier_threshold = 0.5;
  /// Pairs of a scan that must have a consensus to compare with before the scan can be dropped.
  std::size_t min_scan_pairs = 5;
  /// Metres: a scan whose pairs lie farther than this from the similarity (median over its
  /// pairs) is dropped with or without a consensus: a filter lost along a corridor, metres off,
  /// in a part of the building no other scan saw. A bend of 1 m leaves residuals of half that.
  double max_gross_residual = 1.0;
  /// The gross limit is at least this many times the median residual of all pairs (a map
  /// distorted everywhere keeps its pairs).
  double gross_residual_scales = 8.0;
  /// Fraction of the pairs: when more are beyond the gross limit, they are the map's own
  /// distortion, not a lost filter, and none is dropped for it.
  double max_gross_fraction = 0.1;
};

/// Drops the pairs of scans that disagree with the rest (a filter that was wrong, yet
/// converged and consistent): each pair's non-rigid residual (its grid point minus the robust
/// similarity of all pairs) is compared with the median residual of the other scans' pairs in
/// its cell, and a scan whose median deviation exceeds max_deviation loses its pairs; so does a
/// scan whose pairs are grossly off the similarity (max_gross_residual), consensus or not.
/// `pairs_per_scan` gives how many consecutive pairs of `pairs` each scan made (in order); it
/// is updated (0 for a dropped scan). Returns the scans dropped. O(pairs x pairs per cell).
std::size_t reject_outlier_scans(ReferencePairs& pairs, std::vector<std::size_t>& pairs_per_scan,
                                 const OutlierScanOptions& options = {});

}  // namespace floorgrid
