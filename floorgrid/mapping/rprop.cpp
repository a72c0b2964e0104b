#include "floorgrid/mapping/rprop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

[[noreturn]] void fail(const std::string& prefix, const std::string& field,
                       const std::string& what) {
  throw InputError(what, {}, 0, prefix + "." + field);
}

void check_bounds(const Eigen::VectorXd& bound, const std::string& prefix, const char* field,
                  Eigen::Index dimension) {
  if (bound.size() == 0)
    return;
  if (dimension >= 0 && bound.size() != dimension) {
    fail(prefix, field,
         "must be empty or hold one bound per parameter (" + std::to_string(dimension) + "), not " +
             std::to_string(bound.size()));
  }
  for (Eigen::Index i = 0; i < bound.size(); ++i) {
    if (std::isnan(bound[i]))
      fail(prefix, field, "must not be NaN");
  }
}

double sign(double value) {
  return value > 0.0 ? 1.0 : (value < 0.0 ? -1.0 : 0.0);
}

/// Clips x into the box [lower, upper] (either may be empty: unbounded).
Eigen::VectorXd clip(Eigen::VectorXd x, const RpropOptions& options) {
  if (options.lower.size() != 0)
    x = x.cwiseMax(options.lower);
  if (options.upper.size() != 0)
    x = x.cwiseMin(options.upper);
  return x;
}

}  // namespace

void validate_rprop_options(const RpropOptions& options, const std::string& prefix,
                            Eigen::Index dimension) {
  if (!(options.initial_step > 0.0) || !std::isfinite(options.initial_step)) {
    fail(prefix, "initial_step", "must be finite and > 0 " + got(options.initial_step));
  }
  if (!(options.increase > 1.0) || !std::isfinite(options.increase)) {
    fail(prefix, "increase", "must be finite and > 1 " + got(options.increase));
  }
  if (!(options.decrease > 0.0 && options.decrease < 1.0)) {
    fail(prefix, "decrease", "must be in (0, 1) " + got(options.decrease));
  }
  if (!(options.min_step > 0.0) || !std::isfinite(options.min_step)) {
    fail(prefix, "min_step", "must be finite and > 0 " + got(options.min_step));
  }
  if (!(options.max_step >= options.min_step) || !std::isfinite(options.max_step)) {
    fail(prefix, "max_step", "must be finite and >= min_step " + got(options.max_step));
  }
  if (options.max_iterations < 1) {
    fail(prefix, "max_iterations", "must be >= 1 " + got(options.max_iterations));
  }
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance)) {
    fail(prefix, "tolerance", "must be finite and >= 0 " + got(options.tolerance));
  }
  check_bounds(options.lower, prefix, "lower", dimension);
  check_bounds(options.upper, prefix, "upper", dimension);
  if (options.lower.size() != 0 && options.upper.size() != 0) {
    if (options.lower.size() != options.upper.size()) {
      fail(prefix, "upper", "must have as many entries as rprop.lower");
    }
    for (Eigen::Index i = 0; i < options.lower.size(); ++i) {
      if (!(options.lower[i] <= options.upper[i])) {
        fail(prefix, "upper",
             "must be >= lower for every parameter (parameter " + std::to_string(i) + ")");
      }
    }
  }
}

RpropResult minimize_rprop(const RpropObjective& objective, Eigen::VectorXd start,
                           const RpropOptions& options) {
  validate_rprop_options(options, "rprop", start.size());
  if (!start.allFinite())
    throw InputError("must be finite", {}, 0, "rprop.start");
  const Eigen::Index n = start.size();

  RpropResult result;
  Eigen::VectorXd x = clip(std::move(start), options);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
  double value = objective(x, gradient);
  result.iterations = 1;
  result.history.push_back(value);
  result.x = x;
  result.value = value;
  result.gradient = gradient;
  if (!std::isfinite(value)) {
    result.message = "the objective is not finite at the start";
    return result;
  }

  Eigen::VectorXd step = Eigen::VectorXd::Constant(n, options.initial_step);
  Eigen::VectorXd previous_gradient = Eigen::VectorXd::Zero(n);  // as the sign rule sees it
  Eigen::VectorXd previous_step = Eigen::VectorXd::Zero(n);      // the last change of x
  Eigen::VectorXd before_last_step = x;                          // x before that change
  double previous_value = std::numeric_limits<double>::quiet_NaN();
  while (true) {
    if (result.iterations >= options.max_iterations) {
      result.message = "stopped after max_iterations (" + std::to_string(options.max_iterations) +
                       ") evaluations";
      break;
    }
    const bool got_worse = std::isfinite(previous_value) && value > previous_value;
    Eigen::VectorXd next = x;
    Eigen::VectorXd remembered = gradient;
    int reverts = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double product = previous_gradient[i] * gradient[i];
      if (product > 0.0) {
        step[i] = std::min(step[i] * options.increase, options.max_step);
        next[i] = x[i] - sign(gradient[i]) * step[i];
      } else if (product < 0.0) {
        // The last step jumped over a minimum along parameter i.
        step[i] = std::max(step[i] * options.decrease, options.min_step);
        if (got_worse && previous_step[i] != 0.0) {
          next[i] = before_last_step[i];  // exactly where it was, not x - step (rounding)
          ++reverts;
        }
        remembered[i] = 0.0;  // so the next step does not shrink it again
      } else {
        next[i] = x[i] - sign(gradient[i]) * step[i];
      }
    }
    next = clip(next, options);
    if (next == x) {
      // Every parameter flipped without a step back, or is pinned at a bound: evaluating the
      // same point again would waste an iteration and fake convergence, so take the steps the
      // next iteration would take (derivative history cleared) right away.
      for (Eigen::Index i = 0; i < n; ++i)
        next[i] = x[i] - sign(gradient[i]) * step[i];
      remembered = gradient;
      next = clip(next, options);
      if (next == x) {
        result.converged = true;
        result.message = "no parameter can move (zero gradient or pinned at its bounds)";
        break;
      }
    }
    result.reverts += reverts;

    const Eigen::VectorXd last_x = x;
    const Eigen::VectorXd last_gradient = gradient;
    const double last_value = value;
    previous_step = next - x;
    before_last_step = x;
    previous_gradient = remembered;
    x = next;
    value = objective(x, gradient);
    ++result.iterations;
    result.history.push_back(value);
    if (!std::isfinite(value)) {
      // Infeasible point: go back to the last one and try again with every step shrunk.
      ++result.failures;
      x = last_x;
      gradient = last_gradient;
      value = last_value;
      step = (step * options.decrease).cwiseMax(options.min_step);
      previous_gradient.setZero();
      previous_step.setZero();
      continue;
    }
    if (value < result.value) {
      result.x = x;
      result.value = value;
      result.gradient = gradient;
    }
    if (std::abs(value - last_value) < options.tolerance) {
      result.converged = true;
      result.message = "the objective changed by less than the tolerance";
      break;
    }
    previous_value = last_value;
  }
  return result;
}

}  // namespace floorgrid
