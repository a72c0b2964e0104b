#include "floorgrid/localization/divergence.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

bool in_unit_interval(double v) {
  return v >= 0.0 && v <= 1.0;
}

}  // namespace

void validate(const RecoveryOptions& o) {
  require_option(in_unit_interval(o.min_beam_likelihood), "recovery", "min_beam_likelihood",
                 o.min_beam_likelihood, "in [0, 1]");
  require_option(o.max_bad_scans >= 1, "recovery", "max_bad_scans", o.max_bad_scans, ">= 1");
  require_option(o.max_position_std >= 0.0, "recovery", "max_position_std", o.max_position_std,
                 ">= 0 metres");
  require_option(in_unit_interval(o.min_fast_slow_ratio), "recovery", "min_fast_slow_ratio",
                 o.min_fast_slow_ratio, "in [0, 1]");
  require_option(o.alpha_slow > 0.0 && o.alpha_slow <= 1.0, "recovery", "alpha_slow", o.alpha_slow,
                 "in (0, 1]");
  require_option(o.alpha_fast > o.alpha_slow && o.alpha_fast <= 1.0, "recovery", "alpha_fast",
                 o.alpha_fast, "in (alpha_slow, 1]");
  require_option(in_unit_interval(o.max_augmented_fraction), "recovery", "max_augmented_fraction",
                 o.max_augmented_fraction, "in [0, 1]");
  require_option(o.recovery_fraction > 0.0 && o.recovery_fraction <= 1.0, "recovery",
                 "recovery_fraction", o.recovery_fraction, "in (0, 1]");
  require_option(in_unit_interval(o.global_share), "recovery", "global_share", o.global_share,
                 "in [0, 1]");
  require_option(o.initial_radius > 0.0, "recovery", "initial_radius", o.initial_radius,
                 "> 0 metres");
  require_option(o.initial_heading_spread > 0.0, "recovery", "initial_heading_spread",
                 o.initial_heading_spread, "> 0 radians");
  require_option(o.radius_growth >= 1.0, "recovery", "radius_growth", o.radius_growth, ">= 1");
  require_option(o.max_radius >= o.initial_radius, "recovery", "max_radius", o.max_radius,
                 ">= initial_radius");
  require_option(o.max_recovery_scans >= 1, "recovery", "max_recovery_scans", o.max_recovery_scans,
                 ">= 1");
}

std::string_view to_string(DivergenceReason reason) {
  switch (reason) {
    case DivergenceReason::none:
      return "none";
    case DivergenceReason::low_likelihood:
      return "low_likelihood";
    case DivergenceReason::spread:
      return "spread";
    case DivergenceReason::likelihood_drop:
      return "likelihood_drop";
  }
  return "none";
}

DivergenceMonitor::DivergenceMonitor(const RecoveryOptions& options) : options_(options) {
  validate(options_);
}

void DivergenceMonitor::reset() {
  last_ = {};
  w_slow_ = w_fast_ = 0.0;
  has_average_ = false;
}

const DivergenceCheck& DivergenceMonitor::update(double mean_beam_likelihood,
                                                 const PoseEstimate& estimate, bool has_converged) {
  const RecoveryOptions& o = options_;
  if (std::isnan(mean_beam_likelihood)) {
    // No information (the scan ends where the map knows nothing): neither a bad scan nor a
    // good one, and the averages hold; only the spread can still signal.
    const int bad_scans = last_.bad_scans;
    const double ratio = last_.fast_slow_ratio;
    last_ = {};
    last_.bad_scans = bad_scans;
    last_.fast_slow_ratio = ratio;
    if (o.enabled && has_converged && o.max_position_std > 0.0 &&
        !(estimate.position_std <= o.max_position_std))
      last_.reason = DivergenceReason::spread;
    return last_;
  }
  const double w = std::isfinite(mean_beam_likelihood) ? std::max(0.0, mean_beam_likelihood) : 0.0;
  if (!has_average_) {
    w_slow_ = w_fast_ = w;
    has_average_ = true;
  } else {
    w_slow_ += o.alpha_slow * (w - w_slow_);
    w_fast_ += o.alpha_fast * (w - w_fast_);
  }
  const int bad_scans = w < o.min_beam_likelihood ? last_.bad_scans + 1 : 0;
  last_ = {};
  last_.bad_scans = bad_scans;
  last_.fast_slow_ratio = w_slow_ > 0.0 ? w_fast_ / w_slow_ : 1.0;
  last_.augmented_fraction = std::clamp(1.0 - last_.fast_slow_ratio, 0.0, o.max_augmented_fraction);
  if (!o.enabled) {
    last_.augmented_fraction = 0.0;
    return last_;
  }
  if (bad_scans >= o.max_bad_scans) {
    last_.reason = DivergenceReason::low_likelihood;
  } else if (has_converged && o.max_position_std > 0.0 &&
             !(estimate.position_std <= o.max_position_std)) {
    last_.reason = DivergenceReason::spread;
  } else if (has_converged && last_.fast_slow_ratio < o.min_fast_slow_ratio) {
    last_.reason = DivergenceReason::likelihood_drop;
  }
  return last_;
}

}  // namespace floorgrid
