#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

/// How classify_inliers treats the mask it is given.
enum class InlierPassMode {
  /// The mask is overwritten; the moments are those of all inliers.
  full,
  /// The mask holds the previous pass's inliers; the moments are those of the pairs that
  /// joined minus those that left, so adding them to the previous moments gives the new ones.
  delta,
};

/// The sums of one pass over all pairs under a fixed transform.
struct InlierPass {
  PairMoments moments;          ///< of the inliers (full) or of the changes (delta)
  double squared = 0.0;         ///< m^2: sum of w |T p - q|^2 over the inliers
  std::size_t inliers = 0;      ///< pairs with |T p - q| <= threshold
  std::size_t changed = 0;      ///< mask entries that changed (full: = inliers)
  Eigen::Index first_bad = -1;  ///< first pair with a NaN/infinite value or a negative weight
};

/// One pass over `pairs`: marks in `mask` (resized to the pairs) the pairs with
/// |T_grid_plan p - q| <= inlier_threshold and sums their moments about the given origins.
/// Vectorized over contiguous chunks; with `threads` = 2 the fixed blocks are split between
/// two threads and their sums added in block order, so the result does not depend on it.
InlierPass classify_inliers(const ReferencePairs& pairs,
                            const Eigen::Matrix<double, 2, 3>& T_grid_plan, double inlier_threshold,
                            const Eigen::Vector2d& origin_in_plan,
                            const Eigen::Vector2d& origin_in_grid, InlierPassMode mode,
                            std::vector<std::uint8_t>& mask, int threads);

/// The MSAC cost sum_i w_i min(|T_grid_plan p_i - q_i|^2, inlier_threshold^2) over `pairs`
/// (m^2); NaN when a pair holds NaN.
double msac_cost(const ReferencePairs& pairs, const Eigen::Matrix<double, 2, 3>& T_grid_plan,
                 double inlier_threshold, int threads);

}  // namespace floorgrid
