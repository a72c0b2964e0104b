#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>

namespace floorgrid {

/// The Cholesky factor of a GP's training covariance K + (sn^2 + jitter) I, when it is
/// numerically positive definite: the factorization succeeded and every pivot L_ii^2 is at
/// least half the diagonal term sn^2 + jitter (in exact arithmetic L_ii^2 >= sn^2 + jitter,
/// the smallest eigenvalue's lower bound; a smaller pivot means rounding has taken over).
std::optional<Eigen::LLT<Eigen::MatrixXd>> gp_cholesky(Eigen::MatrixXd covariance,
                                                       double diagonal_term);

/// The log marginal likelihood of a GP with two independent outputs sharing one kernel, and
/// its gradient with respect to the log-hyperparameters (log l_1, log l_2, log sf, log sn).
struct GpLikelihoodValue {
  bool ok = false;  ///< false when K was not numerically positive definite (value is -inf)
  /// log p(Y | X) = sum over the two outputs of -1/2 y^T K^-1 y - 1/2 log|K| - N/2 log(2 pi)
  double value = 0.0;
  Eigen::Vector4d gradient = Eigen::Vector4d::Zero();  ///< d value / d log-parameter
};

/// The log marginal likelihood of fixed training data as a function of the hyperparameters
/// (Rasmussen and Williams, eq. 2.30 and 5.9). The outputs must already be centred (their
/// mean removed: the GP's constant mean). Keeps the per-axis squared differences of the
/// inputs, so repeated evaluations only rebuild K: O(N^2) memory, O(N^3) time per gradient.
class GpMarginalLikelihood {
 public:
  /// `points`: 2 x N inputs (metres); `centred_outputs`: 2 x N outputs minus their means.
  GpMarginalLikelihood(Eigen::Ref<const Eigen::Matrix2Xd> points,
                       Eigen::Ref<const Eigen::Matrix2Xd> centred_outputs);

  /// The value at `log_parameters` (one Cholesky factorization, N^3 / 3 flops).
  GpLikelihoodValue value(const Eigen::Vector4d& log_parameters) const;

  /// The value and its analytic gradient: per output
  /// dL/dtheta = 1/2 tr((alpha alpha^T - K^-1) dK/dtheta), summed over the two outputs
  /// (one factorization and K^-1, about 2 N^3 flops).
  GpLikelihoodValue value_and_gradient(const Eigen::Vector4d& log_parameters) const;

  /// Number of training points.
  Eigen::Index size() const { return outputs_.rows(); }

 private:
  GpLikelihoodValue evaluate(const Eigen::Vector4d& log_parameters, bool with_gradient) const;

  Eigen::MatrixXd dx2_;       ///< (x_i1 - x_j1)^2, N x N
  Eigen::MatrixXd dy2_;       ///< (x_i2 - x_j2)^2, N x N
  Eigen::MatrixX2d outputs_;  ///< centred outputs, one point per row
};

}  // namespace floorgrid
