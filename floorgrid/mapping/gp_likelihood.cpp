#include "floorgrid/mapping/gp_likelihood.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/mapping/gp_kernel.hpp"

namespace floorgrid {

std::optional<Eigen::LLT<Eigen::MatrixXd>> gp_cholesky(Eigen::MatrixXd covariance,
                                                       double diagonal_term) {
  Eigen::LLT<Eigen::MatrixXd> llt(std::move(covariance));
  if (llt.info() != Eigen::Success)
    return std::nullopt;
  const Eigen::VectorXd pivots = llt.matrixLLT().diagonal();
  if (!pivots.allFinite() || pivots.cwiseAbs2().minCoeff() < 0.5 * diagonal_term) {
    return std::nullopt;
  }
  return llt;
}

GpMarginalLikelihood::GpMarginalLikelihood(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                           Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs)
    : outputs_(centred_outputs.transpose()) {
  const Eigen::Index n = points.cols();
  dx2_.resize(n, n);
  dy2_.resize(n, n);
  const Eigen::VectorXd x = points.row(0).transpose();
  const Eigen::VectorXd y = points.row(1).transpose();
  for (Eigen::Index j = 0; j < n; ++j) {
    dx2_.col(j) = (x.array() - x[j]).square().matrix();
    dy2_.col(j) = (y.array() - y[j]).square().matrix();
  }
}

GpLikelihoodValue GpMarginalLikelihood::value(const Eigen::Vector4d& log_parameters) const {
  return evaluate(log_parameters, false);
}

GpLikelihoodValue GpMarginalLikelihood::value_and_gradient(
    const Eigen::Vector4d& log_parameters) const {
  return evaluate(log_parameters, true);
}

GpLikelihoodValue GpMarginalLikelihood::evaluate(const Eigen::Vector4d& log_parameters,
                                                 bool with_gradient) const {
  const GpHyperparameters h = GpHyperparameters::from_log(log_parameters);
  const double inv_lx2 = 1.0 / (h.length_scale.x() * h.length_scale.x());
  const double inv_ly2 = 1.0 / (h.length_scale.y() * h.length_scale.y());
  const double sf2 = h.signal_std * h.signal_std;
  const double sn2 = h.noise_std * h.noise_std;
  const Eigen::Index n = size();

  // The noise-free kernel from the stored squared differences (eq. 3.16 without the delta).
  const Eigen::ArrayXXd d2 = dx2_.array() * inv_lx2 + dy2_.array() * inv_ly2;
  const Eigen::MatrixXd signal =
      (d2 > kGpKernelCutoff).select(0.0, sf2 * (-0.5 * d2).exp()).matrix();
  Eigen::MatrixXd covariance = signal;
  covariance.diagonal().array() += sn2;

  GpLikelihoodValue result;
  const std::optional<Eigen::LLT<Eigen::MatrixXd>> llt = gp_cholesky(covariance, sn2);
  if (!llt) {
    result.value = -std::numeric_limits<double>::infinity();
    return result;
  }
  const Eigen::MatrixX2d alpha = llt->solve(outputs_);
  const double log_det = 2.0 * llt->matrixLLT().diagonal().array().log().sum();
  // Two outputs: twice the determinant and normalization terms of one.
  result.value = -0.5 * (outputs_.array() * alpha.array()).sum() - log_det -
                 static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
  result.ok = std::isfinite(result.value);
  if (!result.ok)
    return result;
  if (!with_gradient)
    return result;

  // W = sum_c alpha_c alpha_c^T - 2 K^-1; dL/dtheta = 1/2 sum_ij W_ij dK_ij/dtheta, with
  // dK/dlog l_d = K_f .* D_d / l_d^2, dK/dlog sf = 2 K_f, dK/dlog sn = 2 sn^2 I.
  Eigen::MatrixXd w = llt->solve(Eigen::MatrixXd::Identity(n, n));
  w *= -2.0;
  w.noalias() += alpha * alpha.transpose();
  const Eigen::ArrayXXd weighted = w.array() * signal.array();
  result.gradient[0] = 0.5 * inv_lx2 * (weighted * dx2_.array()).sum();
  result.gradient[1] = 0.5 * inv_ly2 * (weighted * dy2_.array()).sum();
  result.gradient[2] = weighted.sum();
  result.gradient[3] = sn2 * w.trace();
  result.ok = result.gradient.allFinite();
  return result;
}

}  // namespace floorgrid
