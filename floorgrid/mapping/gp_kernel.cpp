#include "floorgrid/mapping/gp_kernel.hpp"

#include <cmath>
#include <sstream>

#include "floorgrid/core/error.hpp"

namespace floorgrid {
namespace {

void check_positive(double value, const std::string& prefix, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream message;
    message << "must be finite and > 0 (got " << value << ")";
    throw InputError(message.str(), {}, 0, prefix + "." + field);
  }
}

}  // namespace

Eigen::Vector4d GpHyperparameters::to_log() const {
  return {std::log(length_scale.x()), std::log(length_scale.y()), std::log(signal_std),
          std::log(noise_std)};
}

GpHyperparameters GpHyperparameters::from_log(const Eigen::Vector4d& log_parameters) {
  GpHyperparameters h;
  h.length_scale = {std::exp(log_parameters[0]), std::exp(log_parameters[1])};
  h.signal_std = std::exp(log_parameters[2]);
  h.noise_std = std::exp(log_parameters[3]);
  return h;
}

void validate_gp_hyperparameters(const GpHyperparameters& hyperparameters,
                                 const std::string& prefix) {
  check_positive(hyperparameters.length_scale.x(), prefix, "length_scale");
  check_positive(hyperparameters.length_scale.y(), prefix, "length_scale");
  check_positive(hyperparameters.signal_std, prefix, "signal_std");
  check_positive(hyperparameters.noise_std, prefix, "noise_std");
}

double gp_signal_covariance(const GpHyperparameters& hyperparameters, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = (a - b).cwiseQuotient(hyperparameters.length_scale);
  const double sf = hyperparameters.signal_std;
  const double d2 = d.squaredNorm();
  return d2 > kGpKernelCutoff ? 0.0 : sf * sf * std::exp(-0.5 * d2);
}

Eigen::MatrixX2d gp_scaled_points(const GpHyperparameters& hyperparameters,
                                  Eigen::Ref<const Eigen::Matrix2Xd> points) {
  Eigen::MatrixX2d scaled(points.cols(), 2);
  scaled.col(0) = points.row(0).transpose() / hyperparameters.length_scale.x();
  scaled.col(1) = points.row(1).transpose() / hyperparameters.length_scale.y();
  return scaled;
}

void gp_covariance_column(Eigen::Ref<const Eigen::MatrixX2d> scaled_points,
                          const Eigen::Vector2d& scaled_query, double sf2,
                          Eigen::Ref<Eigen::VectorXd> out) {
  const Eigen::ArrayXd d2 = (scaled_points.col(0).array() - scaled_query.x()).square() +
                            (scaled_points.col(1).array() - scaled_query.y()).square();
  out.array() = (d2 > kGpKernelCutoff).select(0.0, sf2 * (-0.5 * d2).exp());
}

Eigen::MatrixXd gp_cross_covariance(const GpHyperparameters& hyperparameters,
                                    Eigen::Ref<const Eigen::Matrix2Xd> a,
                                    Eigen::Ref<const Eigen::Matrix2Xd> b) {
  const Eigen::MatrixX2d scaled_a = gp_scaled_points(hyperparameters, a);
  const double sf2 = hyperparameters.signal_std * hyperparameters.signal_std;
  Eigen::MatrixXd k(a.cols(), b.cols());
  for (Eigen::Index j = 0; j < b.cols(); ++j) {
    const Eigen::Vector2d query = b.col(j).cwiseQuotient(hyperparameters.length_scale);
    gp_covariance_column(scaled_a, query, sf2, k.col(j));
  }
  return k;
}

Eigen::MatrixXd gp_training_covariance(const GpHyperparameters& hyperparameters,
                                       Eigen::Ref<const Eigen::Matrix2Xd> points, double jitter) {
  Eigen::MatrixXd k = gp_cross_covariance(hyperparameters, points, points);
  const double sn = hyperparameters.noise_std;
  k.diagonal().array() += sn * sn + jitter;
  return k;
}

}  // namespace floorgrid
