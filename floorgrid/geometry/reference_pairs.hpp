#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace floorgrid {

/// Metres: a coordinate farther than this from its frame's origin is not physical (a building
/// spans a few kilometres; this is a quarter of the Earth's circumference). Pairs, points and
/// model files beyond it are refused: squared distances of such values overflow.
inline constexpr double kMaxCoordinate = 1e7;

/// Reference pairs: column i of `points_in_plan` corresponds to column i of `points_in_grid`.
/// Metres in both frames; `weights` is empty (every pair weighs 1) or holds one weight per pair.
struct ReferencePairs {
  Eigen::Matrix2Xd points_in_plan;  ///< 2 x N, metres
  Eigen::Matrix2Xd points_in_grid;  ///< 2 x N, metres
  Eigen::VectorXd weights;          ///< N weights >= 0, or empty

  /// Number of pairs.
  Eigen::Index size() const { return points_in_plan.cols(); }
  /// Whether there are no pairs.
  bool empty() const { return size() == 0; }
  /// Weight of pair i (1 when no weights are given).
  double weight(Eigen::Index i) const { return weights.size() == 0 ? 1.0 : weights[i]; }
  /// Whether per-pair weights are present.
  bool has_weights() const { return weights.size() != 0; }
};

/// The pairs at the given indices (in their order; an index may repeat), with their weights.
inline ReferencePairs select_pairs(const ReferencePairs& pairs,
                                   const std::vector<Eigen::Index>& indices) {
  ReferencePairs out;
  const auto n = static_cast<Eigen::Index>(indices.size());
  out.points_in_plan.resize(2, n);
  out.points_in_grid.resize(2, n);
  if (pairs.has_weights())
    out.weights.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index i = indices[static_cast<std::size_t>(k)];
    out.points_in_plan.col(k) = pairs.points_in_plan.col(i);
    out.points_in_grid.col(k) = pairs.points_in_grid.col(i);
    if (pairs.has_weights())
      out.weights[k] = pairs.weights[i];
  }
  return out;
}

}  // namespace floorgrid
