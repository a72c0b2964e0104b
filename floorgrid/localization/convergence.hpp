#pragma once

#include "floorgrid/localization/pose_estimate.hpp"

namespace floorgrid {

/// When a particle filter counts as converged (SPEC "Reference pairs by dual Monte Carlo
/// localization"): pairs are made only while both filters are.
struct ConvergenceOptions {
  double max_position_std = 0.3;  ///< map metres: PoseEstimate::position_std at most this
  double max_heading_std = 0.1;   ///< radians: PoseEstimate::heading_std at most this
  /// PoseEstimate::scale_std at most this; checked only when the particles carry a scale (a 2%
  /// scale error moves an endpoint 10 m away by 0.2 m).
  double max_scale_std = 0.02;
  double min_ess_ratio = 0.05;  ///< N_eff / N at least this, in [0, 1]
  /// Mean beam likelihood at the mean pose and scale at least this, in [0, 1].
  double min_beam_likelihood = 0.3;
  /// Consecutive scans meeting every criterion before the filter counts as converged (>= 1).
  int min_converged_scans = 3;
  /// Consecutive scans failing a criterion before a converged filter stops counting as
  /// converged (>= 1; 1: at the first failing scan).
  int max_failed_scans = 1;
  /// A filter that stopped counting as converged at most this many scans ago (failing every
  /// one since) counts as converged again after min_rejoin_scans consecutive scans that meet
  /// every criterion: one bad scan (a person in front of the laser, a long step that spread the
  /// cloud for a scan) does not make a trusted hypothesis a new guess. 0: never (>= 0).
  int rejoin_window = 2;
  int min_rejoin_scans = 1;  ///< (>= 1)
  /// Consecutive scans the map cannot judge (mean beam likelihood NaN: the scan ends where the
  /// map knows nothing) after which a converged filter stops counting as converged, until
  /// scans it can judge meet every criterion again (0: never). Until then its pose is dead
  /// reckoning, which a turn in place or a few metres off the map's edge make a guess. Off by
  /// default: on fr079, whose gridmap is cropped where the robot drives, a gridmap filter blind
  /// for 37-63 scans in a turn came back up to 19 m off on 8 of 20 seeds while counted
  /// converged; 10 for both filters left 2 of 13 runs with such a stretch, but the plan
  /// filter's own look-alike corridors kept the answer seed-dependent, and the robot's honest
  /// excursions off the map (12 and 48 scans) cost up to 10 points of the converged share.
  int max_blind_scans = 0;
};

/// Throws InputError naming `convergence.<field>` when an option is out of range.
void validate(const ConvergenceOptions& options);

/// The convergence test of one scan.
struct ConvergenceCheck {
  bool position_ok = false;    ///< position_std <= max_position_std
  bool heading_ok = false;     ///< heading_std <= max_heading_std
  bool scale_ok = false;       ///< scale_std <= max_scale_std, or no scale carried
  bool ess_ok = false;         ///< ess_ratio >= min_ess_ratio
  bool beam_ok = false;        ///< mean beam likelihood >= min_beam_likelihood
  bool criteria_met = false;   ///< all of the above, on this scan alone
  bool converged = false;      ///< after the hysteresis (ConvergenceMonitor)
  int consecutive_met = 0;     ///< scans in a row meeting every criterion, this one included
  int consecutive_failed = 0;  ///< scans in a row failing one, this one included
  /// Scans since the filter last counted as converged (0: it does on this scan; large when it
  /// never has).
  int since_converged = 1 << 20;
  /// Scans in a row the map could not judge, this one included.
  int consecutive_blind = 0;
};

/// The criteria of one scan (consecutive counts and `converged` left 0 / false).
/// `has_scale`: whether the particles carry a scale.
ConvergenceCheck check_convergence(const PoseEstimate& estimate, double mean_beam_likelihood,
                                   bool has_scale, const ConvergenceOptions& options);

/// Convergence with hysteresis: slow to trust, quick to distrust. A filter becomes converged
/// after `min_converged_scans` consecutive scans that meet every criterion (one lucky scan of
/// a multimodal cloud is not enough), and stops being converged after `max_failed_scans`
/// consecutive failing scans (by default the first: pairs from a doubtful pose are worse than
/// no pairs).
class ConvergenceMonitor {
 public:
  /// A monitor that has seen no scan. Validates `options`.
  explicit ConvergenceMonitor(const ConvergenceOptions& options = {});

  /// Feeds one scan's estimate and mean beam likelihood; returns its check.
  const ConvergenceCheck& update(const PoseEstimate& estimate, double mean_beam_likelihood,
                                 bool has_scale);
  /// Whether the filter counts as converged after the last scan.
  bool converged() const { return last_.converged; }
  /// The last scan's check.
  const ConvergenceCheck& last() const { return last_; }
  /// Forgets every scan (not converged).
  void reset() { last_ = {}; }
  /// The options.
  const ConvergenceOptions& options() const { return options_; }

 private:
  ConvergenceOptions options_;
  ConvergenceCheck last_;
};

}  // namespace floorgrid
