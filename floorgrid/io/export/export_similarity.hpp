#pragma once

#include <Eigen/Core>
#include <string>

#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::io {

/// The model an export describes: `auto`'s chosen model, any other model itself.
const PointMapping& exported_model(const PointMapping& model);

/// Whether the model is affine everywhere (the gt family), so a few GCPs reproduce it exactly.
bool model_is_affine(const PointMapping& model);

/// The similarity part of a model (what a format that knows only scale, rotation and
/// translation can carry).
struct ModelSimilarity {
  Eigen::Matrix3d T_grid_plan = Eigen::Matrix3d::Identity();  ///< rotation, scale, translation
  double scale = 1.0;                                         ///< grid metres per plan metre
  double yaw = 0.0;        ///< radians, rotation from the plan's axes to the grid's
  bool reflected = false;  ///< the plan is mirrored (no similarity format can carry that)
  bool exact = false;      ///< the model is this similarity (gt, gt-rigid)
  double rms_m = 0.0;      ///< metres: rms of |similarity(p) - model(p)| over the points used
  std::size_t points = 0;  ///< plan points the least-squares fit used (0 when exact)
  std::string source;      ///< how it was found, one line for a file's comment
};

/// The model's similarity: exactly T_grid_plan for gt and gt-rigid, otherwise the least-squares
/// similarity of (p, model(p)) over `points_in_plan` (the pairs' plan points, or samples of the
/// plan) with its rms residual. InputError naming `points` when they cannot determine one.
ModelSimilarity model_similarity(const PointMapping& model,
                                 const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan);

}  // namespace floorgrid::io
