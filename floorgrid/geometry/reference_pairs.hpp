#pragma once

#include <Eigen/Core>

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

}  // namespace floorgrid
