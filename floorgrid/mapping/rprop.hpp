#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace floorgrid {

/// Settings of resilient propagation (RPROP, thesis 3.3.1). Steps are in the units of the
/// parameters being optimized (for the GP: natural-log units, so 0.1 is a 10% change).
struct RpropOptions {
  double initial_step = 0.1;  ///< first step of every parameter, parameter units, > 0
  double increase = 1.2;      ///< eta+: step factor while the gradient keeps its sign, > 1
  double decrease = 0.5;      ///< eta-: step factor after a sign change, in (0, 1)
  double min_step = 1e-6;     ///< smallest step, parameter units, > 0
  double max_step = 1.0;      ///< largest step, parameter units, >= min_step
  int max_iterations = 100;   ///< objective evaluations at most, >= 1
  /// converged when the objective changes by less than this between two successive
  /// evaluations (absolute, objective units), >= 0
  double tolerance = 1e-4;
  /// per-parameter lower bounds (a step is clipped at them), or empty for none
  Eigen::VectorXd lower;
  /// per-parameter upper bounds, or empty for none; lower <= upper
  Eigen::VectorXd upper;
};

/// Checks `options` (and, when `dimension` >= 0, the bounds' sizes against it); throws
/// InputError naming the field as `<prefix>.<field>` (`rprop.increase`, ...).
void validate_rprop_options(const RpropOptions& options, const std::string& prefix = "rprop",
                            Eigen::Index dimension = -1);

/// What minimize_rprop did.
struct RpropResult {
  Eigen::VectorXd x;         ///< the best point evaluated (lowest objective)
  double value = 0.0;        ///< the objective at x
  Eigen::VectorXd gradient;  ///< the objective's gradient at x
  int iterations = 0;        ///< objective evaluations
  int reverts = 0;           ///< single-parameter steps taken back (iRprop+ backtracking)
  int failures = 0;          ///< evaluations whose value was not finite (all steps taken back)
  /// the objective value of every evaluation, in order (non-finite where the objective failed)
  std::vector<double> history;
  /// true when the objective changed by less than the tolerance between two successive
  /// evaluations, or no step could move (zero gradient, or pushing against the bounds)
  bool converged = false;
  std::string message;  ///< why it stopped, in words
};

/// The objective: returns f(x) and writes df/dx into `gradient` (already sized like x). A
/// non-finite return marks x as infeasible (e.g. a failed Cholesky factorization).
using RpropObjective = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& gradient)>;

/// Minimizes `objective` from `start` (clipped into the bounds) by iRprop+ (Igel and Huesken,
/// 2000): every parameter has its own step, grown by `increase` while its partial derivative
/// keeps its sign and shrunk by `decrease` when the sign flips; on a flip the parameter's last
/// step is taken back if the objective got worse (the intended backtracking; thesis eq. 3.28
/// negates the weight instead, a typo) and its derivative is treated as zero for one step, so
/// the step is not shrunk twice. Only the signs of the gradient are used. An evaluation with a
/// non-finite value takes every parameter's last step back and shrinks every step. Stops when
/// the objective changes by less than `tolerance` between successive evaluations, when no
/// parameter can move, or after `max_iterations` evaluations. Throws InputError on bad
/// options; when the objective is not finite at the start, returns at once, not converged.
RpropResult minimize_rprop(const RpropObjective& objective, Eigen::VectorXd start,
                           const RpropOptions& options = {});

}  // namespace floorgrid
