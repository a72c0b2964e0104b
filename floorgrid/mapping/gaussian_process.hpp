#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/mapping/gp_kernel.hpp"
#include "floorgrid/mapping/gp_lattice.hpp"
#include "floorgrid/mapping/gp_tuning.hpp"

namespace floorgrid {

/// How a fitted GP predicts.
struct GpPredictionOptions {
  GpLatticeOptions lattice;       ///< the mean's lattice (fast, within lattice.tolerance metres)
  int threads = kDefaultThreads;  ///< threads for batches and the lattice, 1 or 2; results do not
                                  ///< depend on it
};

/// How fit_gaussian_process works.
struct GaussianProcessOptions {
  /// given: used as they are (no tuning); empty: tuned by RPROP on the log marginal likelihood
  std::optional<GpHyperparameters> hyperparameters;
  GpTuningOptions tuning;          ///< subsample, bounds and RPROP settings of the tuning
  GpPredictionOptions prediction;  ///< lattice and threads of the fitted model
  /// refuse more training points than this (K takes 8 N^2 bytes and N^3 / 3 flops); the
  /// caller reduces the pairs first; >= 3
  Eigen::Index max_points = 4000;
};

/// Checks `options`; throws InputError naming the field (`gaussian_process.tuning.max_points`,
/// `gaussian_process.prediction.threads`, ...).
void validate_gaussian_process_options(const GaussianProcessOptions& options);

/// Everything a fitted GP needs to predict, as plain data for the model file. The Cholesky
/// factor and the mean's lattice are not stored: they are recomputed from the inputs,
/// hyperparameters and jitter when a GaussianProcess is built from this; with the same
/// GpPredictionOptions its predictions are bit-identical to the fitted model's (the same code
/// computes them), provided the doubles are saved exactly (17 significant digits).
struct GaussianProcessState {
  Eigen::Matrix2Xd inputs;  ///< 2 x N training inputs, metres (plan points)
  /// 2 x N, row c: (K + (sn^2 + jitter) I)^-1 (y_c - output_mean_c), 1/metre
  Eigen::Matrix2Xd alpha;
  Eigen::Vector2d output_mean = Eigen::Vector2d::Zero();  ///< the GP's constant mean, metres
  GpHyperparameters hyperparameters;                      ///< kernel, metres
  double jitter = 0.0;  ///< m^2 added to K's diagonal besides sn^2 so that Cholesky succeeded
};

struct GaussianProcessFit;

/// A Gaussian process from R^2 to R^2 (thesis 3.3, 4.4.1): two independent outputs with one
/// squared-exponential ARD kernel and a constant mean per output (the outputs' mean, so the
/// mean reverts to it far from data; thesis eq. 3.21-3.23 with y centred). One Cholesky
/// factor serves both outputs, and the predictive std is the same for both.
///
/// mean() evaluates a bicubic Hermite lattice of the mean inside the training points'
/// bounding box plus a margin (error measured at build time, within
/// GpLatticeOptions::tolerance) and the exact formula outside it; exact_mean() always uses the
/// formula m + k_*^T alpha. Immutable after construction: safe to share between threads.
class GaussianProcess {
 public:
  /// Rebuilds a GP from its state (e.g. read from a model file): validates it (InputError
  /// naming `gaussian_process.<field>`), recomputes the Cholesky factor and the lattice.
  explicit GaussianProcess(GaussianProcessState state, const GpPredictionOptions& options = {});

  /// The plain data to save.
  const GaussianProcessState& state() const { return state_; }
  /// Number of training points.
  Eigen::Index size() const { return state_.inputs.cols(); }
  /// The kernel's hyperparameters.
  const GpHyperparameters& hyperparameters() const { return state_.hyperparameters; }
  /// The mean's lattice (empty when disabled or too fine for max_nodes).
  const GpMeanLattice& lattice() const { return lattice_; }
  /// The prediction options in use.
  const GpPredictionOptions& prediction_options() const { return options_; }

  /// The predictive mean at `point` (plan metres): lattice inside it, exact outside.
  Eigen::Vector2d mean(const Eigen::Vector2d& point) const;
  /// mean() of every column of `points` (2 x M), in blocks on up to `threads` threads.
  Eigen::Matrix2Xd mean_batch(Eigen::Ref<const Eigen::Matrix2Xd> points) const;
  /// The exact predictive mean m + k_*^T alpha (eq. 3.22), O(N).
  Eigen::Vector2d exact_mean(const Eigen::Vector2d& point) const;
  /// exact_mean() of every column of `points` (2 x M).
  Eigen::Matrix2Xd exact_mean_batch(Eigen::Ref<const Eigen::Matrix2Xd> points) const;
  /// The Jacobian of the function mean() evaluates (entry (c, d) = d mean_c / d point_d):
  /// the lattice patch's derivative inside the lattice, the exact one outside, so that Newton
  /// iterations on mean() converge quadratically.
  Eigen::Matrix2d mean_jacobian(const Eigen::Vector2d& point) const;
  /// The exact Jacobian of exact_mean(): sum_i alpha_ci dk(point, x_i)/dpoint_d.
  Eigen::Matrix2d exact_mean_jacobian(const Eigen::Vector2d& point) const;

  /// The predictive standard deviation at `point`, metres, the same for both outputs: of the
  /// latent function, sqrt(sf^2 - k_*^T K^-1 k_*) (eq. 3.23), or with `include_noise` of a
  /// new observation (plus sn^2). Exact, O(N^2).
  double standard_deviation(const Eigen::Vector2d& point, bool include_noise = false) const;
  /// standard_deviation() of every column of `points`, in blocks of 256 points (a triangular
  /// solve with many right-hand sides) on up to `threads` threads; equal to the single-point
  /// version up to rounding.
  Eigen::VectorXd standard_deviation_batch(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                           bool include_noise = false) const;

 private:
  // The fit hands over its Cholesky factor instead of having it computed again.
  friend GaussianProcessFit fit_gaussian_process(Eigen::Ref<const Eigen::Matrix2Xd>,
                                                 Eigen::Ref<const Eigen::Matrix2Xd>,
                                                 const GaussianProcessOptions&);
  GaussianProcess(GaussianProcessState state, Eigen::LLT<Eigen::MatrixXd> cholesky,
                  const GpPredictionOptions& options);
  void finish_construction();
  Eigen::Vector2d scaled(const Eigen::Vector2d& point) const;

  GaussianProcessState state_;
  GpPredictionOptions options_;
  Eigen::LLT<Eigen::MatrixXd> cholesky_;  ///< of K + (sn^2 + jitter) I
  Eigen::MatrixX2d scaled_inputs_;        ///< inputs / length scales, one per row
  Eigen::MatrixX2d alpha_columns_;        ///< alpha transposed, N x 2
  GpMeanLattice lattice_;
};

/// What fit_gaussian_process did.
struct GaussianProcessSummary {
  Eigen::Index training_points = 0;  ///< N, all conditioned on
  bool tuned = false;                ///< false when the hyperparameters were given
  Eigen::Index tuning_points = 0;    ///< size of the spread subsample tuned on (0: not tuned)
  int iterations = 0;                ///< RPROP evaluations (0: not tuned)
  int reverts = 0;                   ///< RPROP steps taken back
  bool converged = false;            ///< RPROP met its tolerance (true when not tuned)
  std::vector<double> history;       ///< log marginal likelihood on the subsample, per iteration
  double tuning_log_marginal_likelihood = 0.0;  ///< on the subsample at the result
  double log_marginal_likelihood = 0.0;         ///< on all N points at the result
  GpHyperparameters initial;                    ///< RPROP's start (when tuned)
  GpHyperparameters hyperparameters;            ///< the ones used
  GpHyperparameterBounds bounds;                ///< the tuning box (when tuned)
  /// hyperparameters that ended at a bound (`noise_std@lower`, ...; see GpTuningResult)
  std::vector<std::string> at_bounds;
  double jitter = 0.0;  ///< m^2 added to K's diagonal (0 unless Cholesky failed)
  Eigen::Vector2d lattice_spacing = Eigen::Vector2d::Zero();  ///< metres (0: no lattice)
  Eigen::Index lattice_nodes = 0;                             ///< nodes (0: no lattice)
  double lattice_error = 0.0;  ///< measured max |lattice - exact| mean, metres
  std::string message;         ///< what was done, in words
};

/// A fitted GP and how it was fitted.
struct GaussianProcessFit {
  GaussianProcess model;           ///< ready to predict
  GaussianProcessSummary summary;  ///< tuning and conditioning report
};

/// Fits a GP from `inputs` (2 x N plan points, metres) to `outputs` (2 x N, metres: grid
/// coordinates, or residuals of a global transform): centres the outputs (constant mean),
/// tunes the hyperparameters on a spread subsample unless given, conditions on all N points
/// (adding jitter to K's diagonal, reported, if its Cholesky factorization fails) and builds
/// the mean's lattice. Throws InputError naming `pairs` for fewer than 3 points, differing
/// counts, non-finite values, all inputs equal or more than max_points, and naming the
/// option for bad options. Deterministic: the same data and options give the same bits.
GaussianProcessFit fit_gaussian_process(Eigen::Ref<const Eigen::Matrix2Xd> inputs,
                                        Eigen::Ref<const Eigen::Matrix2Xd> outputs,
                                        const GaussianProcessOptions& options = {});

}  // namespace floorgrid
