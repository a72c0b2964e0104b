#include "floorgrid/mapping/gp_tuning.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/mapping/gp_likelihood.hpp"

namespace floorgrid {
namespace {

[[noreturn]] void fail(const std::string& prefix, const char* field, const std::string& what,
                       double value) {
  std::ostringstream message;
  message << what << " (got " << value << ")";
  throw InputError(message.str(), {}, 0, prefix + "." + field);
}

Eigen::Matrix2Xd gather(Eigen::Ref<const Eigen::Matrix2Xd> points,
                        const std::vector<Eigen::Index>& indices) {
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(indices.size()));
  for (std::size_t i = 0; i < indices.size(); ++i) {
    out.col(static_cast<Eigen::Index>(i)) = points.col(indices[i]);
  }
  return out;
}

/// The median distance from each point to its nearest other point (O(N^2)).
double median_nearest_neighbour_distance(Eigen::Ref<const Eigen::Matrix2Xd> points) {
  const Eigen::Index n = points.cols();
  std::vector<double> nearest(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd d2 = (points.colwise() - points.col(i)).colwise().squaredNorm().transpose();
    d2[i] = std::numeric_limits<double>::infinity();
    nearest[static_cast<std::size_t>(i)] = std::sqrt(d2.minCoeff());
  }
  return upper_median(std::move(nearest));
}

double extent(Eigen::Ref<const Eigen::Matrix2Xd> points) {
  return (points.rowwise().maxCoeff() - points.rowwise().minCoeff()).maxCoeff();
}

double output_rms(Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs) {
  return std::sqrt(centred_outputs.squaredNorm() / static_cast<double>(centred_outputs.size()));
}

Eigen::Vector4d clip(const Eigen::Vector4d& x, const Eigen::Vector4d& lower,
                     const Eigen::Vector4d& upper) {
  return x.cwiseMax(lower).cwiseMin(upper);
}

}  // namespace

void validate_gp_tuning_options(const GpTuningOptions& options, const std::string& prefix) {
  if (options.max_points < 3) {
    fail(prefix, "max_points", "must be >= 3", options.max_points);
  }
  if (!(options.min_noise_std > 0.0) || !std::isfinite(options.min_noise_std)) {
    fail(prefix, "min_noise_std", "must be finite and > 0 (metres)", options.min_noise_std);
  }
  if (!(options.min_length_scale_factor > 0.0) || !std::isfinite(options.min_length_scale_factor)) {
    fail(prefix, "min_length_scale_factor", "must be finite and > 0",
         options.min_length_scale_factor);
  }
  if (!(options.min_length_scale_extent >= 0.0) ||
      !(options.min_length_scale_extent <= options.max_length_scale_factor)) {
    fail(prefix, "min_length_scale_extent", "must be >= 0 and <= max_length_scale_factor",
         options.min_length_scale_extent);
  }
  if (!(options.max_length_scale_factor > 0.0) || !std::isfinite(options.max_length_scale_factor)) {
    fail(prefix, "max_length_scale_factor", "must be finite and > 0",
         options.max_length_scale_factor);
  }
  if (!(options.max_signal_std_factor > 0.0) || !std::isfinite(options.max_signal_std_factor)) {
    fail(prefix, "max_signal_std_factor", "must be finite and > 0", options.max_signal_std_factor);
  }
  validate_rprop_options(options.rprop, prefix + ".rprop", 4);
  if (options.rprop.lower.size() != 0 || options.rprop.upper.size() != 0) {
    throw InputError("must be empty: the tuning sets the bounds itself", {}, 0,
                     prefix + ".rprop.lower");
  }
}

std::vector<Eigen::Index> gp_spread_subsample(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                              Eigen::Index count) {
  const Eigen::Index n = points.cols();
  std::vector<Eigen::Index> chosen;
  if (count >= n) {
    chosen.resize(static_cast<std::size_t>(n));
    std::iota(chosen.begin(), chosen.end(), Eigen::Index{0});
    return chosen;
  }
  if (count <= 0)
    return chosen;
  const Eigen::Vector2d centroid = points.rowwise().mean();
  Eigen::Index next = 0;
  (points.colwise() - centroid).colwise().squaredNorm().minCoeff(&next);
  // Squared distance to the nearest chosen point; -1 marks chosen ones.
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  while (static_cast<Eigen::Index>(chosen.size()) < count) {
    chosen.push_back(next);
    nearest =
        nearest.cwiseMin((points.colwise() - points.col(next)).colwise().squaredNorm().transpose());
    nearest[next] = -1.0;     // stays -1 under cwiseMin
    nearest.maxCoeff(&next);  // Eigen returns the first maximum: ties go to the lowest index
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

GpHyperparameterBounds gp_hyperparameter_bounds(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                                Eigen::Ref<const Eigen::Matrix2Xd> tuning_points,
                                                Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs,
                                                const GpTuningOptions& options) {
  const double e = extent(points);
  const double spacing = std::max(median_nearest_neighbour_distance(tuning_points), 1e-6 * e);
  const double r = output_rms(centred_outputs);
  const double floor = options.min_noise_std;

  GpHyperparameterBounds bounds;
  const double max_length = options.max_length_scale_factor * e;
  const double min_length = std::min(
      std::max(options.min_length_scale_factor * spacing, options.min_length_scale_extent * e),
      max_length);
  bounds.lower.length_scale = Eigen::Vector2d::Constant(min_length);
  bounds.upper.length_scale = Eigen::Vector2d::Constant(max_length);
  bounds.lower.signal_std = floor;
  bounds.upper.signal_std = options.max_signal_std_factor * std::max(r, floor);
  bounds.upper.signal_std = std::max(bounds.upper.signal_std, floor);
  bounds.lower.noise_std = floor;
  bounds.upper.noise_std = std::max(r, 10.0 * floor);
  return bounds;
}

GpTuningResult tune_gp_hyperparameters(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                       Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs,
                                       const GpTuningOptions& options) {
  validate_gp_tuning_options(options, "gaussian_process.tuning");
  const std::vector<Eigen::Index> subsample = gp_spread_subsample(points, options.max_points);
  const Eigen::Matrix2Xd tuning_points = gather(points, subsample);
  const Eigen::Matrix2Xd tuning_outputs = gather(centred_outputs, subsample);

  GpTuningResult result;
  result.tuning_points = tuning_points.cols();
  result.bounds = gp_hyperparameter_bounds(points, tuning_points, tuning_outputs, options);
  const Eigen::Vector4d lower = result.bounds.lower.to_log();
  const Eigen::Vector4d upper = result.bounds.upper.to_log();

  const GpMarginalLikelihood likelihood(tuning_points, tuning_outputs);

  // A few likelihood values (one Cholesky each) pick RPROP's start, which only follows
  // gradient signs and so depends on where it begins.
  const double e = extent(points);
  const double r = std::max(output_rms(tuning_outputs), options.min_noise_std);
  Eigen::Vector4d start = Eigen::Vector4d::Zero();
  double best = -std::numeric_limits<double>::infinity();
  for (const double length_factor : {0.05, 0.15, 0.5, 1.5}) {
    for (const double noise_factor : {0.01, 0.1}) {
      GpHyperparameters guess;
      guess.length_scale = Eigen::Vector2d::Constant(length_factor * e);
      guess.signal_std = r;
      guess.noise_std = noise_factor * r;
      const Eigen::Vector4d candidate = clip(guess.to_log(), lower, upper);
      const GpLikelihoodValue value = likelihood.value(candidate);
      if (value.ok && value.value > best) {
        best = value.value;
        start = candidate;
      }
    }
  }
  if (!std::isfinite(best))
    start = clip(Eigen::Vector4d::Zero(), lower, upper);
  result.initial = GpHyperparameters::from_log(start);

  RpropOptions rprop = options.rprop;
  rprop.lower = lower;
  rprop.upper = upper;
  const RpropObjective negative_log_likelihood = [&likelihood](const Eigen::VectorXd& x,
                                                               Eigen::VectorXd& gradient) {
    const GpLikelihoodValue value = likelihood.value_and_gradient(x);
    if (!value.ok)
      return std::numeric_limits<double>::infinity();
    gradient = -value.gradient;
    return -value.value;
  };
  result.rprop = minimize_rprop(negative_log_likelihood, start, rprop);
  result.hyperparameters = GpHyperparameters::from_log(result.rprop.x);
  result.log_marginal_likelihood = -result.rprop.value;

  const char* names[4] = {"length_scale_x", "length_scale_y", "signal_std", "noise_std"};
  for (int i = 0; i < 4; ++i) {
    if (result.rprop.x[i] <= lower[i] + 1e-9)
      result.at_bounds.push_back(names[i] + std::string("@lower"));
    if (result.rprop.x[i] >= upper[i] - 1e-9)
      result.at_bounds.push_back(names[i] + std::string("@upper"));
  }
  return result;
}

}  // namespace floorgrid
