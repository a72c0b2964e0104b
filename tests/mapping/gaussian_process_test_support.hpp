#pragma once

// Data for the Gaussian-process tests: uniform points and outputs drawn from a GP prior with
// known hyperparameters.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/gp_kernel.hpp"

namespace floorgrid::test {

/// `count` uniform random points in [0, width] x [0, height].
inline Eigen::Matrix2Xd uniform_points(Random& random, Eigen::Index count, double width,
                                       double height) {
  Eigen::Matrix2Xd points(2, count);
  for (Eigen::Index i = 0; i < count; ++i) {
    points.col(i) << random.uniform(0.0, width), random.uniform(0.0, height);
  }
  return points;
}

/// Two independent draws of a GP with `h` at `points` (2 x N): the latent function sampled
/// from N(0, K_f) plus noise of std h.noise_std.
inline Eigen::Matrix2Xd gp_sample(Random& random, const GpHyperparameters& h,
                                  const Eigen::Matrix2Xd& points) {
  Eigen::MatrixXd k = gp_cross_covariance(h, points, points);
  // A tiny relative jitter makes the prior's K factorizable; it changes samples by ~1e-5 sf.
  k.diagonal().array() += 1e-10 * h.signal_std * h.signal_std;
  const Eigen::LLT<Eigen::MatrixXd> llt(k);
  Eigen::MatrixXd z(points.cols(), 2);
  for (Eigen::Index i = 0; i < z.size(); ++i)
    z.data()[i] = random.normal();
  Eigen::Matrix2Xd sample = (llt.matrixL() * z).transpose();
  for (Eigen::Index i = 0; i < sample.size(); ++i)
    sample.data()[i] += random.normal(h.noise_std);
  return sample;
}

/// Hyperparameters from their values.
inline GpHyperparameters hyperparameters(double lx, double ly, double sf, double sn) {
  GpHyperparameters h;
  h.length_scale = {lx, ly};
  h.signal_std = sf;
  h.noise_std = sn;
  return h;
}

}  // namespace floorgrid::test
