#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace floorgrid {

/// The families of global plan-to-grid transforms (SPEC models `gt`, `gt-rigid`, `gt-affine`).
enum class TransformKind {
  similarity,  ///< rotation, uniform scale and translation (a mirror on top when allowed)
  rigid,       ///< rotation and translation, scale fixed at 1 (a mirror on top when allowed)
  affine,      ///< any linear map and a translation; a mirror is part of the family
};

/// Whether a similarity or rigid fit may be mirrored (det of its linear part < 0). Affine fits
/// ignore it: an affine map is mirrored exactly when its data is.
enum class Reflection {
  forbid,   ///< proper transforms only (det > 0)
  allow,    ///< mirrored when that fits better (det of the cross-covariance < 0); ties: proper
  require,  ///< mirrored transforms only
};

/// "similarity", "rigid" or "affine".
const char* transform_kind_name(TransformKind kind);

/// The pairs a minimal sample of `kind` needs: 2 for similarity and rigid, 3 for affine.
int minimal_sample_size(TransformKind kind);

/// Options of the weighted least-squares transform fit.
struct TransformEstimationOptions {
  TransformKind kind = TransformKind::similarity;  ///< the family fitted
  /// Similarity and rigid: whether a mirrored plan may be fitted. Collinear data cannot tell a
  /// mirror from a proper transform; `allow` then chooses the proper one.
  Reflection reflection = Reflection::allow;
};

/// A fitted plan-to-grid transform.
struct TransformEstimate {
  /// Homogeneous 3x3: a point p in the plan maps to T_grid_plan * (p, 1) in the grid.
  Eigen::Matrix3d T_grid_plan = Eigen::Matrix3d::Identity();
  double scale = 1.0;      ///< similarity: the uniform scale; rigid: 1; affine: sqrt(|det|)
  bool reflected = false;  ///< whether the linear part has det < 0 (a mirrored plan)
  double rms = 0.0;        ///< metres: weighted rms of |T p - q| over the pairs fitted
};

/// Weighted sufficient statistics of point pairs, summed about fixed origins (one per frame) so
/// that large coordinates do not cancel. Every least-squares fit of a TransformKind needs only
/// these, so a pass over millions of pairs can accumulate them while it classifies inliers.
struct PairMoments {
  Eigen::Vector2d origin_in_plan = Eigen::Vector2d::Zero();  ///< metres, subtracted from p
  Eigen::Vector2d origin_in_grid = Eigen::Vector2d::Zero();  ///< metres, subtracted from q
  double weight = 0.0;                                       ///< sum of w
  Eigen::Vector2d plan = Eigen::Vector2d::Zero();            ///< sum of w p'
  Eigen::Vector2d grid = Eigen::Vector2d::Zero();            ///< sum of w q'
  Eigen::Matrix2d plan_plan = Eigen::Matrix2d::Zero();       ///< sum of w p' p'^T
  Eigen::Matrix2d grid_plan = Eigen::Matrix2d::Zero();       ///< sum of w q' p'^T
  double grid_grid = 0.0;                                    ///< sum of w |q'|^2

  /// Adds the pair (point_in_plan, point_in_grid) with weight `w` (p' = p - origin_in_plan).
  void add(const Eigen::Vector2d& point_in_plan, const Eigen::Vector2d& point_in_grid,
           double w = 1.0);
  /// Adds moments summed about the same origins.
  PairMoments& operator+=(const PairMoments& other);
};

/// The weighted least-squares fit of `options.kind` to summed moments: Umeyama's closed form
/// for similarity and rigid (in 2-D the SVD of the cross-covariance reduces to one angle),
/// normal equations of the centred data for affine. Returns std::nullopt when the moments do
/// not determine a transform (see degeneracy_reason). `rms` is computed from the moments, so it
/// carries rounding of about 1e-8 of the pairs' extent.
std::optional<TransformEstimate> fit_transform(const PairMoments& moments,
                                               const TransformEstimationOptions& options);

/// Why `moments` determine no transform of `options.kind` (empty when they do): no positive
/// weight; fewer than 2 distinct plan points (similarity, rigid); collinear plan points
/// (affine); coincident grid points (similarity); no proper/mirrored rotation fitting at all.
std::string degeneracy_reason(const PairMoments& moments,
                              const TransformEstimationOptions& options);

/// Weighted least-squares T_grid_plan minimizing sum_i w_i |T p_i - q_i|^2 over the family
/// `options.kind` (column i of `points_in_plan` pairs with column i of `points_in_grid`;
/// `weights` empty means all 1). Thesis eq. 3.5-3.11 with scale and reflection added, and the
/// translation t = c_G - s R c_F applied once (eq. 3.13 applies it twice). `rms` is exact.
/// Throws InputError naming `pairs` on mismatched sizes, NaN/infinite coordinates, negative or
/// NaN weights, and degenerate input (see degeneracy_reason).
TransformEstimate estimate_transform(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                     const Eigen::Ref<const Eigen::VectorXd>& weights,
                                     const TransformEstimationOptions& options = {});

/// estimate_transform with every weight 1.
TransformEstimate estimate_transform(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                     const TransformEstimationOptions& options = {});

}  // namespace floorgrid
