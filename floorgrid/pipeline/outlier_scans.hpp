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
};

/// Drops the pairs of scans that disagree with the rest (a filter that was wrong, yet
/// converged and consistent): each pair's non-rigid residual (its grid point minus the robust
/// similarity of all pairs) is compared with the median residual of the other scans' pairs in
/// its cell, and a scan whose median deviation exceeds max_deviation loses its pairs.
/// `pairs_per_scan` gives how many consecutive pairs of `pairs` each scan made (in order); it
/// is updated (0 for a dropped scan). Returns the scans dropped. O(pairs x pairs per cell).
std::size_t reject_outlier_scans(ReferencePairs& pairs, std::vector<std::size_t>& pairs_per_scan,
                                 const OutlierScanOptions& options = {});

}  // namespace floorgrid
