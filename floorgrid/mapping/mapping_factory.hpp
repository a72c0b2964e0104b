#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/ransac.hpp"
#include "floorgrid/mapping/error_model.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"
#include "floorgrid/mapping/linear_combination.hpp"
#include "floorgrid/mapping/local_transforms.hpp"
#include "floorgrid/mapping/model_registry.hpp"
#include "floorgrid/mapping/model_selection.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/mapping/thin_plate_spline_mapping.hpp"

namespace floorgrid {

/// Every model's options, defaults in one place; `model` picks the model.
struct MappingOptions {
  std::string model = "auto";   ///< lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps, auto
  MappingCommonOptions common;  ///< shared: reduction budget, extrapolation distance, seed
  RansacOptions ransac;         ///< gt variants (and gpgt's global part); kind set by model
  /// metres: gpgt's RANSAC inlier distance (its other RANSAC options are `ransac`'s). Unset:
  /// adapted to the pairs' noise like gt's; the residuals of a similarity on a bent map are its
  /// bends, so the threshold widens with them and the similarity carries the bulk of the map
  /// (the GP takes the bends). A fixed value should be wide for the same reason (0.5 m was the
  /// default before).
  std::optional<double> gpgt_inlier_threshold;
  LinearCombinationOptions lc;      ///< lc
  LocalTransformsOptions ct;        ///< ct
  GaussianProcessOptions gp;        ///< gp and gpgt
  ThinPlateSplineModelOptions tps;  ///< tps
  AutoOptions auto_select;          ///< auto: candidates and cross-validation
  ErrorModelOptions uncertainty;    ///< every model's std_m, from its blocked cross-validation
};

/// A new, unfitted model (model_registry's entry for `options.model`). InputError (field "model")
/// for an unknown name.
std::unique_ptr<PointMapping> make_mapping(const MappingOptions& options);

}  // namespace floorgrid
