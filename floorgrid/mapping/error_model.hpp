#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>

#include "floorgrid/geometry/point_index.hpp"

namespace floorgrid {

/// One pair held out by a spatially blocked cross-validation: how far the model fitted without
/// its block missed it, and how far it lay from the pairs that model saw.
struct HeldOutResidual {
  double error_m = 0.0;    ///< |model(plan point) - grid point|, metres
  double nearest_m = 0.0;  ///< plan metres from its plan point to the nearest training pair
  Eigen::Vector2d point_in_plan = Eigen::Vector2d::Zero();  ///< where it was held out
};

/// How an error model is fitted.
struct ErrorModelOptions {
  /// Held-out pairs needed at least: with fewer the model states no std_m.
  std::size_t min_residuals = 30;
  /// Factor on the fitted variance when the model's level is not known (see ErrorLevel), tuned
  /// on the simulator's presets and ACES seed 1 when the error model was introduced: the
  /// held-out errors include the pairs' own noise, which a model's error at a point does not.
  double variance_scale = 0.7;
  /// The level's floor, as a fraction of the runs folds' held-out root mean square error: the
  /// pairs' noise is estimated, and where it is estimated at or above the held-out error the
  /// model's own error is not zero.
  double min_level_fraction = 0.2;
  /// Metres: radius (Gaussian sigma) over which the held-out errors around a point say how much
  /// worse or better than the global fit the model is there (0: no local part).
  double local_radius = 1.0;
  /// Pseudo-count of the global fit in that local average (more: closer to the global fit).
  double local_prior = 1.0;
  /// Metres: a bias every pair shares, which no cross-validation over the pairs can see (a plan
  /// scale off by a fraction of a percent, a plan filter pulled along a corridor, wall faces
  /// against the drawn strokes), added to every std_m in quadrature (0: none). align sets it
  /// from the two pair sources' disagreement (align.sources.shared_bias).
  double shared_std = 0.0;
};

/// Checks `options`; throws InputError naming `<prefix><field>`.
void validate(const ErrorModelOptions& options, const char* prefix = "mapping.uncertainty.");

/// A mapping model's predictive error at a plan point p whose nearest reference pair is d
/// metres away: var(p) = f(p) (s0^2 + (g d)^2) + b^2, the variance of the 2D error vector (E|e|^2,
/// both axes together). std_m = sqrt(var) is the root mean square length of the error: for an
/// isotropic Gaussian error |e| <= std_m holds 63% of the time and |e| <= 2 std_m 98%.
/// s0 carries what no posterior over the pairs sees (pair errors correlated along a scan and a
/// wall, the model's misfit), g the growth away from the pairs, both fitted by maximum
/// likelihood on spatially blocked cross-validation residuals; f(p) is the local misfit: the
/// held-out errors near p over what s0 and g expect of them, a Gaussian-weighted mean shrunk
/// towards 1 (where the model errs more than elsewhere, its std is larger there). b is a bias
/// the pairs share (ErrorModelOptions::shared_std), the same everywhere.
struct ErrorModel {
  double base_std_m = 0.0;      ///< s0: metres, at a pair
  double growth = 0.0;          ///< g: metres of std per metre from the nearest pair
  std::size_t residuals = 0;    ///< held-out pairs it was fitted on
  double max_nearest_m = 0.0;   ///< the farthest held-out pair from its training pairs, metres
  double local_radius_m = 0.0;  ///< the local part's radius (0: none)
  double local_prior = 1.0;     ///< the global fit's pseudo-count in the local mean
  double shared_std_m = 0.0;    ///< b: metres, the pairs' shared bias
  /// The held-out pairs' plan points and their squared error over s0^2 + (g d)^2.
  Eigen::Matrix2Xd local_points;
  Eigen::VectorXd local_ratios;  ///< one per local point, >= 0

  /// std_m at `nearest_m` metres from the nearest pair, without the local part (b included).
  double std_at(double nearest_m) const;
  /// std_m at `point_in_plan`, `nearest_m` metres from the nearest pair.
  double std_at(const Eigen::Vector2d& point_in_plan, double nearest_m) const;
  /// f(p): the local factor at a plan point (1 without a local part).
  double local_factor(const Eigen::Vector2d& point_in_plan) const;
  /// Indexes local_points (after setting them by hand, as a model file's reader does).
  void index_local_points();

 private:
  PointIndex2D local_index_;
};

/// What sets the model's own error level (fit_error_model): held-out pairs of folds of whole
/// runs, whose places other visits measured, and the pairs' own noise (pair_noise). A runs
/// residual at d from its training pairs has E|e|^2 = k^2 (s0^2 + (g d)^2) + E|n|^2: the model's
/// error there (the blocked fit's shape, scaled by k^2) plus the held-out pair's own noise,
/// which a model's error at a point does not carry.
struct ErrorLevel {
  std::span<const HeldOutResidual> held_out;  ///< runs folds' held-out pairs
  double pair_noise_m2 = 0.0;                 ///< the pairs' E|n|^2, m^2
};

/// Fits s0 and g by maximum likelihood on `residuals` (each error a 2D isotropic Gaussian of
/// variance var(d): its length is Rayleigh distributed), keeps the local part, and scales the
/// variance: by k^2 solved from `level`'s moments, at least min_level_fraction^2 of the runs
/// residuals' mean square over the shape's (the blocked residuals give the shape: how the error
/// grows away from the pairs and where it is larger); by options.variance_scale without a
/// level. nullopt with fewer than options.min_residuals finite residuals.
std::optional<ErrorModel> fit_error_model(std::span<const HeldOutResidual> residuals,
                                          const ErrorModelOptions& options = {},
                                          std::optional<ErrorLevel> level = std::nullopt);

}  // namespace floorgrid
