#pragma once

#include <Eigen/Core>
#include <string>

namespace floorgrid {

/// The kernel is exactly 0 where the squared scaled distance sum_d (dx_d / l_d)^2 exceeds this
/// (beyond 17.3 length scales, where it is below e^-150 sf^2 ~ 7e-66 sf^2 anyway): products of
/// such values would otherwise reach subnormal numbers, whose arithmetic is ~100 times slower.
inline constexpr double kGpKernelCutoff = 300.0;

/// Hyperparameters of the squared-exponential kernel with one length scale per input axis
/// (ARD), thesis eq. 3.16:
///   k(x, x') = signal_std^2 exp(-1/2 sum_d (x_d - x'_d)^2 / length_scale_d^2)
///              + noise_std^2 [x and x' are the same training point].
/// Inputs and outputs are metres, so every hyperparameter is in metres.
struct GpHyperparameters {
  Eigen::Vector2d length_scale{1.0, 1.0};  ///< l_1, l_2: metres along the input x and y, > 0
  double signal_std = 1.0;                 ///< sf: metres, the latent function's prior std, > 0
  double noise_std = 0.01;                 ///< sn: metres, the outputs' noise std, > 0

  /// (log l_1, log l_2, log sf, log sn): the parameters RPROP tunes.
  Eigen::Vector4d to_log() const;
  /// The inverse of to_log().
  static GpHyperparameters from_log(const Eigen::Vector4d& log_parameters);
};

/// Checks that every hyperparameter is finite and > 0; throws InputError naming
/// `<prefix>.length_scale`, `<prefix>.signal_std` or `<prefix>.noise_std`.
void validate_gp_hyperparameters(const GpHyperparameters& hyperparameters,
                                 const std::string& prefix);

/// The noise-free part of the kernel, k_f(a, b) = sf^2 exp(-1/2 sum_d (a_d - b_d)^2 / l_d^2)
/// (0 beyond kGpKernelCutoff).
double gp_signal_covariance(const GpHyperparameters& hyperparameters, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b);

/// The noise-free cross-covariance K(a, b): entry (i, j) is k_f(a_i, b_j), a.cols() x b.cols().
Eigen::MatrixXd gp_cross_covariance(const GpHyperparameters& hyperparameters,
                                    Eigen::Ref<const Eigen::Matrix2Xd> a,
                                    Eigen::Ref<const Eigen::Matrix2Xd> b);

/// The training covariance K(x, x) + (sn^2 + jitter) I of `points` (thesis eq. 3.17); `jitter`
/// is an extra diagonal term in m^2 (0 normally).
Eigen::MatrixXd gp_training_covariance(const GpHyperparameters& hyperparameters,
                                       Eigen::Ref<const Eigen::Matrix2Xd> points,
                                       double jitter = 0.0);

/// The points divided by the length scales, one point per row (N x 2, so that each coordinate
/// is contiguous for vectorized kernel evaluation): row i is (x_i1 / l_1, x_i2 / l_2).
Eigen::MatrixX2d gp_scaled_points(const GpHyperparameters& hyperparameters,
                                  Eigen::Ref<const Eigen::Matrix2Xd> points);

/// k_f(query, x_i) for every training point into `out` (sized scaled_points.rows()), from
/// gp_scaled_points() of the training points, the query divided by the length scales and
/// sf2 = sf^2.
void gp_covariance_column(Eigen::Ref<const Eigen::MatrixX2d> scaled_points,
                          const Eigen::Vector2d& scaled_query, double sf2,
                          Eigen::Ref<Eigen::VectorXd> out);

}  // namespace floorgrid
