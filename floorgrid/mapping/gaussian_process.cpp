#include "floorgrid/mapping/gaussian_process.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"
#include "floorgrid/mapping/gp_likelihood.hpp"

namespace floorgrid {
namespace {

// Fixed work splits (not tied to the thread count, so results are not either).
constexpr Eigen::Index kMeanBlock = 4096;  // points per task of the batch mean
constexpr Eigen::Index kStdBlock = 256;    // right-hand sides per triangular solve

[[noreturn]] void bad_pairs(const std::string& what) {
  throw InputError(what, {}, 0, "pairs");
}

void validate_pairs(Eigen::Ref<const Eigen::Matrix2Xd> inputs,
                    Eigen::Ref<const Eigen::Matrix2Xd> outputs, Eigen::Index max_points) {
  const Eigen::Index n = inputs.cols();
  if (outputs.cols() != n) {
    bad_pairs("the plan side has " + std::to_string(n) + " points and the other side " +
              std::to_string(outputs.cols()));
  }
  if (n < 3) {
    bad_pairs("the Gaussian process needs at least 3 pairs (got " + std::to_string(n) + ")");
  }
  if (n > max_points) {
    bad_pairs(std::to_string(n) + " pairs exceed gaussian_process.max_points (" +
              std::to_string(max_points) + "): reduce the pairs first");
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!inputs.col(i).allFinite() || !outputs.col(i).allFinite()) {
      bad_pairs("pair " + std::to_string(i) + " (counting from 0) is not finite");
    }
  }
  if ((inputs.rowwise().maxCoeff() - inputs.rowwise().minCoeff()).maxCoeff() == 0.0) {
    bad_pairs("all " + std::to_string(n) +
              " plan points are equal: the Gaussian process needs distinct points");
  }
}

void validate_prediction_options(const GpPredictionOptions& options, const std::string& prefix) {
  validate_gp_lattice_options(options.lattice, prefix + ".lattice");
  if (options.threads < 1 || options.threads > 2) {
    throw InputError("must be 1 or 2 (got " + std::to_string(options.threads) + ")", {}, 0,
                     prefix + ".threads");
  }
}

/// The Cholesky factor of K + (sn^2 + jitter) I, or nullopt; K is built afresh every time so
/// that a GP rebuilt from its state gets the very same bits.
std::optional<Eigen::LLT<Eigen::MatrixXd>> factor(const GpHyperparameters& h,
                                                  Eigen::Ref<const Eigen::Matrix2Xd> inputs,
                                                  double jitter) {
  return gp_cholesky(gp_training_covariance(h, inputs, jitter), h.noise_std * h.noise_std + jitter);
}

/// Factors K, adding jitter (from max(sn^2, 1e-12 sf^2), times 10 per failure) until it is
/// numerically positive definite; with jitter >= sf^2 it always is (condition number <= N + 1).
std::pair<Eigen::LLT<Eigen::MatrixXd>, double> factor_with_jitter(
    const GpHyperparameters& h, Eigen::Ref<const Eigen::Matrix2Xd> inputs) {
  if (std::optional<Eigen::LLT<Eigen::MatrixXd>> llt = factor(h, inputs, 0.0)) {
    return {std::move(*llt), 0.0};
  }
  const double sf2 = h.signal_std * h.signal_std;
  double jitter = std::max(h.noise_std * h.noise_std, 1e-12 * sf2);
  while (true) {
    if (std::optional<Eigen::LLT<Eigen::MatrixXd>> llt = factor(h, inputs, jitter)) {
      return {std::move(*llt), jitter};
    }
    jitter *= 10.0;
  }
}

}  // namespace

void validate_gaussian_process_options(const GaussianProcessOptions& options) {
  if (options.hyperparameters) {
    validate_gp_hyperparameters(*options.hyperparameters, "gaussian_process.hyperparameters");
  }
  validate_gp_tuning_options(options.tuning, "gaussian_process.tuning");
  validate_prediction_options(options.prediction, "gaussian_process.prediction");
  if (options.max_points < 3) {
    throw InputError("must be >= 3 (got " + std::to_string(options.max_points) + ")", {}, 0,
                     "gaussian_process.max_points");
  }
}

GaussianProcess::GaussianProcess(GaussianProcessState state, const GpPredictionOptions& options)
    : state_(std::move(state)), options_(options) {
  validate_prediction_options(options_, "gaussian_process.prediction");
  const Eigen::Index n = state_.inputs.cols();
  if (n < 1 || !state_.inputs.allFinite()) {
    throw InputError("must hold at least one point, all finite", {}, 0, "gaussian_process.inputs");
  }
  if (state_.alpha.cols() != n || !state_.alpha.allFinite()) {
    throw InputError("must hold one finite column per input (" + std::to_string(n) + "), not " +
                         std::to_string(state_.alpha.cols()),
                     {}, 0, "gaussian_process.alpha");
  }
  if (!state_.output_mean.allFinite()) {
    throw InputError("must be finite", {}, 0, "gaussian_process.output_mean");
  }
  validate_gp_hyperparameters(state_.hyperparameters, "gaussian_process.hyperparameters");
  if (!(state_.jitter >= 0.0) || !std::isfinite(state_.jitter)) {
    throw InputError("must be finite and >= 0", {}, 0, "gaussian_process.jitter");
  }
  std::optional<Eigen::LLT<Eigen::MatrixXd>> llt =
      factor(state_.hyperparameters, state_.inputs, state_.jitter);
  if (!llt) {
    throw InputError("the training covariance is not positive definite with this jitter", {}, 0,
                     "gaussian_process.jitter");
  }
  cholesky_ = std::move(*llt);
  finish_construction();
}

GaussianProcess::GaussianProcess(GaussianProcessState state, Eigen::LLT<Eigen::MatrixXd> cholesky,
                                 const GpPredictionOptions& options)
    : state_(std::move(state)), options_(options), cholesky_(std::move(cholesky)) {
  finish_construction();
}

void GaussianProcess::finish_construction() {
  scaled_inputs_ = gp_scaled_points(state_.hyperparameters, state_.inputs);
  alpha_columns_ = state_.alpha.transpose();
  lattice_ = GpMeanLattice::build(state_.hyperparameters, state_.inputs, state_.alpha,
                                  options_.lattice, options_.threads);
}

Eigen::Vector2d GaussianProcess::scaled(const Eigen::Vector2d& point) const {
  return point.cwiseQuotient(state_.hyperparameters.length_scale);
}

Eigen::Vector2d GaussianProcess::mean(const Eigen::Vector2d& point) const {
  if (lattice_.contains(point))
    return state_.output_mean + lattice_.value(point);
  return exact_mean(point);
}

Eigen::Matrix2Xd GaussianProcess::mean_batch(Eigen::Ref<const Eigen::Matrix2Xd> points) const {
  Eigen::Matrix2Xd out(2, points.cols());
  parallel_chunks(static_cast<std::size_t>(points.cols()), kMeanBlock, options_.threads,
                  [&](Eigen::Index begin, Eigen::Index end) {
                    for (Eigen::Index j = begin; j < end; ++j)
                      out.col(j) = mean(points.col(j));
                  });
  return out;
}

Eigen::Vector2d GaussianProcess::exact_mean(const Eigen::Vector2d& point) const {
  const double sf = state_.hyperparameters.signal_std;
  Eigen::VectorXd k(size());
  gp_covariance_column(scaled_inputs_, scaled(point), sf * sf, k);
  return state_.output_mean + alpha_columns_.transpose() * k;  // eq. 3.22 per output
}

Eigen::Matrix2Xd GaussianProcess::exact_mean_batch(
    Eigen::Ref<const Eigen::Matrix2Xd> points) const {
  Eigen::Matrix2Xd out(2, points.cols());
  parallel_chunks(static_cast<std::size_t>(points.cols()), kMeanBlock, options_.threads,
                  [&](Eigen::Index begin, Eigen::Index end) {
                    for (Eigen::Index j = begin; j < end; ++j) {
                      out.col(j) = exact_mean(points.col(j));
                    }
                  });
  return out;
}

Eigen::Matrix2d GaussianProcess::mean_jacobian(const Eigen::Vector2d& point) const {
  if (lattice_.contains(point))
    return lattice_.jacobian(point);
  return exact_mean_jacobian(point);
}

Eigen::Matrix2d GaussianProcess::exact_mean_jacobian(const Eigen::Vector2d& point) const {
  const double sf = state_.hyperparameters.signal_std;
  const Eigen::Vector2d q = scaled(point);
  Eigen::VectorXd k(size());
  gp_covariance_column(scaled_inputs_, q, sf * sf, k);
  // dk/dx_d = -k (x_d - x_id) / l_d^2 = -k (q_d - s_id) / l_d in scaled coordinates.
  Eigen::Matrix2d jacobian;
  for (int d = 0; d < 2; ++d) {
    const Eigen::VectorXd weighted = (k.array() * (q[d] - scaled_inputs_.col(d).array())).matrix();
    jacobian.col(d) =
        -(alpha_columns_.transpose() * weighted) / state_.hyperparameters.length_scale[d];
  }
  return jacobian;
}

double GaussianProcess::standard_deviation(const Eigen::Vector2d& point, bool include_noise) const {
  const Eigen::Matrix2Xd one = point;
  return standard_deviation_batch(one, include_noise)[0];
}

Eigen::VectorXd GaussianProcess::standard_deviation_batch(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                                          bool include_noise) const {
  const double sf2 = state_.hyperparameters.signal_std * state_.hyperparameters.signal_std;
  const double sn2 = state_.hyperparameters.noise_std * state_.hyperparameters.noise_std;
  Eigen::VectorXd out(points.cols());
  parallel_chunks(
      static_cast<std::size_t>(points.cols()), kStdBlock, options_.threads,
      [&](Eigen::Index begin, Eigen::Index end) {
        // eq. 3.23: k** - k*^T K^-1 k* = sf^2 - |L^-1 k*|^2.
        Eigen::MatrixXd v(size(), end - begin);
        for (Eigen::Index j = begin; j < end; ++j) {
          gp_covariance_column(scaled_inputs_, scaled(points.col(j)), sf2, v.col(j - begin));
        }
        cholesky_.matrixL().solveInPlace(v);
        const Eigen::ArrayXd latent =
            (sf2 - v.colwise().squaredNorm().transpose().array()).max(0.0);
        out.segment(begin, end - begin) = (include_noise ? latent + sn2 : latent).sqrt().matrix();
      });
  return out;
}

GaussianProcessFit fit_gaussian_process(Eigen::Ref<const Eigen::Matrix2Xd> inputs,
                                        Eigen::Ref<const Eigen::Matrix2Xd> outputs,
                                        const GaussianProcessOptions& options) {
  validate_gaussian_process_options(options);
  validate_pairs(inputs, outputs, options.max_points);
  const Eigen::Index n = inputs.cols();

  GaussianProcessSummary summary;
  summary.training_points = n;
  GaussianProcessState state;
  state.inputs = inputs;
  state.output_mean = outputs.rowwise().mean();
  const Eigen::Matrix2Xd centred = outputs.colwise() - state.output_mean;

  std::ostringstream message;
  if (options.hyperparameters) {
    state.hyperparameters = *options.hyperparameters;
    summary.converged = true;
    message << "hyperparameters given; ";
  } else {
    GpTuningResult tuning = tune_gp_hyperparameters(inputs, centred, options.tuning);
    state.hyperparameters = tuning.hyperparameters;
    summary.tuned = true;
    summary.tuning_points = tuning.tuning_points;
    summary.iterations = tuning.rprop.iterations;
    summary.reverts = tuning.rprop.reverts;
    summary.converged = tuning.rprop.converged;
    for (const double value : tuning.rprop.history)
      summary.history.push_back(-value);
    summary.tuning_log_marginal_likelihood = tuning.log_marginal_likelihood;
    summary.initial = tuning.initial;
    summary.bounds = tuning.bounds;
    summary.at_bounds = std::move(tuning.at_bounds);
    message << "tuned on " << tuning.tuning_points << " of " << n << " points by RPROP ("
            << tuning.rprop.iterations << " iterations, " << tuning.rprop.message << ")";
    for (const std::string& bound : summary.at_bounds)
      message << ", " << bound;
    message << "; ";
  }
  summary.hyperparameters = state.hyperparameters;

  auto [llt, jitter] = factor_with_jitter(state.hyperparameters, inputs);
  state.jitter = jitter;
  summary.jitter = jitter;
  const Eigen::MatrixX2d alpha = llt.solve(centred.transpose());
  state.alpha = alpha.transpose();
  summary.log_marginal_likelihood = -0.5 * (centred.transpose().array() * alpha.array()).sum() -
                                    2.0 * llt.matrixLLT().diagonal().array().log().sum() -
                                    static_cast<double>(n) * std::log(2.0 * std::numbers::pi);
  message << "conditioned on " << n << " points";
  if (jitter > 0.0)
    message << " with jitter " << jitter << " m^2";

  GaussianProcess model(std::move(state), std::move(llt), options.prediction);
  const GpMeanLattice& lattice = model.lattice();
  if (!lattice.empty()) {
    summary.lattice_spacing = lattice.spacing();
    summary.lattice_nodes = lattice.nodes_x() * lattice.nodes_y();
    summary.lattice_error = lattice.measured_error();
  }
  message << "; lattice: " << lattice.message();
  summary.message = message.str();
  return {std::move(model), std::move(summary)};
}

}  // namespace floorgrid
