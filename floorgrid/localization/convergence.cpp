#include "floorgrid/localization/convergence.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
void validate(const ConvergenceOptions& o) {
  require_option(o.max_position_std > 0.0, "convergence", "max_position_std", o.max_position_std,
                 "> 0 metres");
  require_option(o.max_heading_std > 0.0, "convergence", "max_heading_std", o.max_heading_std,
                 "> 0 radians");
  require_option(o.max_scale_std > 0.0, "convergence", "max_scale_std", o.max_scale_std, "> 0");
  require_option(o.min_ess_ratio >= 0.0 && o.min_ess_ratio <= 1.0, "convergence", "min_ess_ratio",
                 o.min_ess_ratio, "in [0, 1]");
  require_option(o.min_beam_likelihood >= 0.0 && o.min_beam_likelihood <= 1.0, "convergence",
                 "min_beam_likelihood", o.min_beam_likelihood, "in [0, 1]");
  require_option(o.min_converged_scans >= 1, "convergence", "min_converged_scans",
                 o.min_converged_scans, ">= 1");
  require_option(o.max_failed_scans >= 1, "convergence", "max_failed_scans", o.max_failed_scans,
                 ">= 1");
  require_option(o.rejoin_window >= 0, "convergence", "rejoin_window", o.rejoin_window, ">= 0");
  require_option(o.max_blind_scans >= 0, "convergence", "max_blind_scans", o.max_blind_scans,
                 ">= 0");
  require_option(o.min_rejoin_scans >= 1, "convergence", "min_rejoin_scans", o.min_rejoin_scans,
                 ">= 1");
}

ConvergenceCheck check_convergence(const PoseEstimate& estimate, double mean_beam_likelihood,
                                   bool has_scale, const ConvergenceOptions& options) {
  ConvergenceCheck c;
  // Written as "within" tests so that NaN fails them.
  c.position_ok = estimate.position_std <= options.max_position_std;
  c.heading_ok = estimate.heading_std <= options.max_heading_std;
  c.scale_ok = !has_scale || estimate.scale_std <= options.max_scale_std;
  c.ess_ok = estimate.ess_ratio >= options.min_ess_ratio;
  c.beam_ok = mean_beam_likelihood >= options.min_beam_likelihood;
  c.criteria_met = c.position_ok && c.heading_ok && c.scale_ok && c.ess_ok && c.beam_ok;
  return c;
}

ConvergenceMonitor::ConvergenceMonitor(const ConvergenceOptions& options) : options_(options) {
  validate(options_);
}

const ConvergenceCheck& ConvergenceMonitor::update(const PoseEstimate& estimate,
                                                   double mean_beam_likelihood, bool has_scale) {
  const ConvergenceCheck previous = last_;
  last_ = check_convergence(estimate, mean_beam_likelihood, has_scale, options_);
  if (std::isnan(mean_beam_likelihood)) {
    // The map cannot judge this scan (it ends where the map knows nothing): the fit criterion
    // keeps its last verdict, so a converged filter stays converged on the other criteria and
    // an unconverged one cannot converge on it.
    last_.consecutive_blind = previous.consecutive_blind + 1;
    // ... for at most max_blind_scans scans: longer blind, the fit is no longer vouched for.
    last_.beam_ok = previous.beam_ok && (options_.max_blind_scans == 0 ||
                                         last_.consecutive_blind <= options_.max_blind_scans);
    last_.criteria_met =
        last_.position_ok && last_.heading_ok && last_.scale_ok && last_.ess_ok && last_.beam_ok;
  }
  last_.consecutive_met = last_.criteria_met ? previous.consecutive_met + 1 : 0;
  last_.consecutive_failed = last_.criteria_met ? 0 : previous.consecutive_failed + 1;
  if (previous.converged) {
    last_.converged = last_.consecutive_failed < options_.max_failed_scans;
  } else {
    // Dropped a few scans ago (at most rejoin_window failing scans since), then meeting every
    // criterion again: the same hypothesis, trusted again sooner.
    const int failed = previous.since_converged + 1 - last_.consecutive_met;
    last_.converged =
        last_.consecutive_met >= options_.min_converged_scans ||
        (last_.consecutive_met >= options_.min_rejoin_scans && failed <= options_.rejoin_window);
  }
  last_.since_converged = last_.converged ? 0 : std::min(previous.since_converged, 1 << 20) + 1;
  return last_;
}

}  // namespace floorgrid
