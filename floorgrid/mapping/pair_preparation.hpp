#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid {

/// Throws InputError (field "pairs") when a pair has a non-finite coordinate or weight, a
/// negative weight, or the plan and grid sides differ in size.
void validate_pairs(const ReferencePairs& pairs);

/// What merge_duplicates did.
struct DuplicateMerge {
  std::size_t merged = 0;         ///< pairs folded into another with the same plan point
  std::size_t conflicting = 0;    ///< of those, ones whose grid points differ by more than 1 cm
  double largest_conflict = 0.0;  ///< metres between the grid points of one plan point
};

/// Merges pairs with exactly equal plan points into one: the weighted mean of their grid
/// points, the sum of their weights. A conflicting duplicate (one plan point, two grid points
/// far apart) so stays finite; it is counted so the caller can warn.
ReferencePairs merge_duplicates(const ReferencePairs& pairs, DuplicateMerge* report = nullptr);

/// How reduce_pairs bins pairs.
struct ReductionOptions {
  std::size_t budget = 1500;  ///< at most this many pairs after reduction, >= 3
};

/// What reduce_pairs did.
struct ReductionSummary {
  bool applied = false;          ///< false when the pairs were within the budget
  std::size_t pairs_before = 0;  ///< pairs given
  std::size_t pairs_after = 0;   ///< pairs returned
  double cell_size = 0.0;        ///< metres, side of the square plan cells (0 when not applied)
};

/// Reduces pairs to the budget by spatial binning in the plan: square cells of the smallest
/// size that leaves at most `budget` non-empty cells; each cell's pairs become one pair, the
/// weighted mean of those whose displacement (grid - plan) is within 3 median absolute
/// deviations of the cell's median displacement (so a stray pair does not drag a cell), with
/// their summed weight. Pairs within the budget are returned unchanged. Deterministic. A few
/// pairs far from the rest (see far_pairs) each keep a cell of their own and leave the cells of
/// the others as small as without them.
ReferencePairs reduce_pairs(const ReferencePairs& pairs, const ReductionOptions& options,
                            ReductionSummary* summary = nullptr);

/// At most `budget` of the pairs, evenly spread along their order (every k-th, k fractional),
/// in that order, with their weights; all of them when within the budget.
ReferencePairs thin_in_order(const ReferencePairs& pairs, std::size_t budget);

/// Axis-aligned extent of the plan points: the length of the bounds' diagonal, metres.
double plan_extent(const ReferencePairs& pairs);

/// Whether all plan points lie on one line (within `tolerance` times the extent).
bool plan_points_collinear(const ReferencePairs& pairs, double tolerance = 1e-9);

/// Number of distinct plan points.
std::size_t distinct_plan_points(const ReferencePairs& pairs);

}  // namespace floorgrid
