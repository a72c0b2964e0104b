#include "floorgrid/mapping/error_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "floorgrid/core/validation.hpp"

namespace floorgrid {

void validate(const ErrorModelOptions& options, const char* prefix) {
  const std::string p = prefix;
  require_option(options.min_residuals >= 3, p + "min_residuals", options.min_residuals, ">= 3");
  require_option(options.variance_scale > 0.0 && options.variance_scale <= 1e6,
                 p + "variance_scale", options.variance_scale, "in (0, 1e6]");
  require_option(options.min_level_fraction > 0.0 && options.min_level_fraction <= 1.0,
                 p + "min_level_fraction", options.min_level_fraction, "in (0, 1]");
  require_option(options.local_radius >= 0.0 && options.local_radius <= 1e3, p + "local_radius",
                 options.local_radius, "in [0, 1000] metres");
  require_option(options.local_prior > 0.0 && options.local_prior <= 1e6, p + "local_prior",
                 options.local_prior, "in (0, 1e6]");
  require_option(options.shared_std >= 0.0 && options.shared_std <= 1e3, p + "shared_std",
                 options.shared_std, "in [0, 1000] metres");
}

namespace {

/// sqrt(factor (s0^2 + (g d)^2) + b^2).
double combined_std(const ErrorModel& m, double nearest_m, double factor) {
  const double spread = m.growth * nearest_m;
  return std::sqrt(factor * (m.base_std_m * m.base_std_m + spread * spread) +
                   m.shared_std_m * m.shared_std_m);
}

}  // namespace

double ErrorModel::std_at(double nearest_m) const {
  return combined_std(*this, nearest_m, 1.0);
}

double ErrorModel::local_factor(const Eigen::Vector2d& p) const {
  if (local_radius_m <= 0.0 || local_index_.size() == 0)
    return 1.0;
  // Gaussian weights, cut at 3 sigma; the global fit counts as local_prior pairs of ratio 1.
  double weight = local_prior, sum = local_prior;
  const double two_var = 2.0 * local_radius_m * local_radius_m;
  for (const PointIndex2D::Neighbour& n : local_index_.within(p, 3.0 * local_radius_m)) {
    const double w = std::exp(-n.distance * n.distance / two_var);
    weight += w;
    sum += w * local_ratios[n.index];
  }
  return sum / weight;
}

double ErrorModel::std_at(const Eigen::Vector2d& p, double nearest_m) const {
  return combined_std(*this, nearest_m, local_factor(p));
}

void ErrorModel::index_local_points() {
  local_index_ = PointIndex2D(local_points);
}

namespace {

/// Negative log-likelihood (up to a constant) of error lengths r_i, each the length of a 2D
/// isotropic Gaussian vector with E|e|^2 = s0^2 + (g d_i)^2 (Rayleigh: log v + r^2 / v).
double negative_log_likelihood(const std::vector<HeldOutResidual>& residuals, double s0, double g) {
  double sum = 0.0;
  for (const HeldOutResidual& r : residuals) {
    const double spread = g * r.nearest_m;
    const double v = s0 * s0 + spread * spread;
    sum += std::log(v) + r.error_m * r.error_m / v;
  }
  return sum;
}

struct Estimate {
  double log_s0 = 0.0;
  double log_g = 0.0;  ///< g = 0 below kNoGrowth
  double nll = std::numeric_limits<double>::infinity();
};

/// log10 g below this means no growth (g = 0).
constexpr double kNoGrowth = -5.0;

double growth_of(double log_g) {
  return log_g <= kNoGrowth ? 0.0 : std::pow(10.0, log_g);
}

/// The best (log10 s0, log10 g) on a grid of `steps` x `steps` points around `centre` spanning
/// +-`half` decades, g = 0 included at the grid's low end.
Estimate search(const std::vector<HeldOutResidual>& residuals, const Estimate& centre,
                double half_s0, double half_g, int steps) {
  Estimate best = centre;
  for (int i = 0; i <= steps; ++i) {
    const double log_s0 = centre.log_s0 - half_s0 + 2.0 * half_s0 * i / steps;
    for (int k = 0; k <= steps; ++k) {
      const double log_g = std::max(kNoGrowth, centre.log_g - half_g + 2.0 * half_g * k / steps);
      const double nll =
          negative_log_likelihood(residuals, std::pow(10.0, log_s0), growth_of(log_g));
      if (nll < best.nll)
        best = {log_s0, log_g, nll};
    }
  }
  return best;
}

/// k (see ErrorLevel) from the runs residuals' moments: their mean square less the pairs'
/// noise (at least min_fraction^2 of their mean square) over the shape's mean there; nullopt
/// without a finite residual.
std::optional<double> level_scale(const ErrorLevel& level, double s0, double g,
                                  double min_fraction) {
  double errors = 0.0, shape = 0.0;
  std::size_t count = 0;
  for (const HeldOutResidual& r : level.held_out) {
    if (!std::isfinite(r.error_m) || !std::isfinite(r.nearest_m))
      continue;
    const double spread = g * r.nearest_m;
    errors += r.error_m * r.error_m;
    shape += s0 * s0 + spread * spread;
    ++count;
  }
  if (count == 0 || !(shape > 0.0))
    return std::nullopt;
  const double own = std::max(errors - static_cast<double>(count) * level.pair_noise_m2,
                              min_fraction * min_fraction * errors);
  return std::sqrt(own / shape);
}

}  // namespace

std::optional<ErrorModel> fit_error_model(std::span<const HeldOutResidual> given,
                                          const ErrorModelOptions& options,
                                          std::optional<ErrorLevel> level) {
  std::vector<HeldOutResidual> residuals;
  residuals.reserve(given.size());
  double max_nearest = 0.0;
  for (const HeldOutResidual& r : given) {
    if (std::isfinite(r.error_m) && std::isfinite(r.nearest_m) && r.nearest_m >= 0.0) {
      residuals.push_back(r);
      max_nearest = std::max(max_nearest, r.nearest_m);
    }
  }
  if (residuals.size() < options.min_residuals)
    return std::nullopt;
  // Coarse to fine over log10 s0 in [-4, 1] (0.1 mm to 10 m) and log10 g in [-5, 1].
  Estimate best{-1.5, -2.0, std::numeric_limits<double>::infinity()};
  best = search(residuals, best, 2.5, 3.0, 30);
  for (double half = 0.2; half > 1e-3; half *= 0.25)
    best = search(residuals, best, half, half, 8);
  ErrorModel model;
  const double s0 = std::pow(10.0, best.log_s0), g = growth_of(best.log_g);
  if (options.local_radius > 0.0) {
    model.local_radius_m = options.local_radius;
    model.local_prior = options.local_prior;
    model.local_points.resize(2, static_cast<Eigen::Index>(residuals.size()));
    model.local_ratios.resize(static_cast<Eigen::Index>(residuals.size()));
    for (std::size_t i = 0; i < residuals.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const double spread = g * residuals[i].nearest_m;
      model.local_points.col(k) = residuals[i].point_in_plan;
      model.local_ratios[k] =
          residuals[i].error_m * residuals[i].error_m / (s0 * s0 + spread * spread);
    }
    model.index_local_points();
  }
  const std::optional<double> levelled =
      level ? level_scale(*level, s0, g, options.min_level_fraction) : std::nullopt;
  const double scale = levelled ? *levelled : std::sqrt(options.variance_scale);
  model.base_std_m = scale * s0;
  model.growth = scale * g;
  model.shared_std_m = options.shared_std;
  model.residuals = residuals.size();
  model.max_nearest_m = max_nearest;
  return model;
}

}  // namespace floorgrid
