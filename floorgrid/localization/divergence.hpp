#pragma once

#include <string_view>

#include "floorgrid/localization/pose_estimate.hpp"

namespace floorgrid {

/// When a tracking filter counts as diverged (lost), and how it recovers (SPEC: "recovery when
/// a filter diverges"). Detection runs only while tracking; see ParticleFilter for the states.
struct RecoveryOptions {
  bool enabled = true;  ///< false: never declare divergence and never inject particles

  // ---- detection: any one of the three signals ----
  /// A scan is bad when the mean beam likelihood at the mean pose is below this, in [0, 1]
  /// (half ConvergenceOptions::min_beam_likelihood: between the two a filter is merely
  /// not converged).
  double min_beam_likelihood = 0.15;
  /// This many consecutive bad scans while tracking mean diverged (>= 1). Counts from the
  /// tracking start, so a wrong initial pose is caught within these scans. During global
  /// localization it marks a cloud that collapsed onto one pose (spread within the
  /// convergence limits) that does not fit.
  int max_bad_scans = 5;
  /// Map metres: after having converged, a position spread above this means diverged (the
  /// cloud has exploded); 0 disables the signal.
  double max_position_std = 1.0;
  /// After having converged, w_fast / w_slow below this means diverged (the recent fit is far
  /// worse than the long-term one); 0 disables the signal. In [0, 1].
  double min_fast_slow_ratio = 0.3;
  /// Per-scan smoothing of the long-term average likelihood w_slow, in (0, 1] (augmented MCL,
  /// Probabilistic Robotics 8.3.5); ~1/alpha scans of memory.
  double alpha_slow = 0.01;
  /// Per-scan smoothing of the short-term average likelihood w_fast, in (0, 1], > alpha_slow.
  double alpha_fast = 0.2;

  // ---- augmented MCL while tracking ----
  /// While tracking, replace max(0, 1 - w_fast / w_slow) of the particles, at most this share
  /// (in [0, 1]; 0 disables), by particles drawn from the global distribution (free space when
  /// the filter knows it, otherwise around the estimate at max_radius).
  double max_augmented_fraction = 0.25;

  // ---- recovery after divergence ----
  /// Share of the particles replaced on every recovering scan, in (0, 1].
  double recovery_fraction = 0.3;
  /// Of those, the share drawn uniformly over the free space (when the filter knows it), in
  /// [0, 1]; the rest is drawn around the anchor: the last good estimate carried along by the
  /// odometry, or a better-fitting estimate found while recovering.
  double global_share = 0.5;
  /// Metres (map): radius of the disc around the anchor when the anchor is set (> 0).
  double initial_radius = 0.5;
  /// Radians: heading spread (uniform +-) around the anchor's heading when the anchor is set
  /// (> 0); grows like the radius up to pi.
  double initial_heading_spread = 0.3;
  /// Factor by which radius and heading spread grow per recovering scan on which no estimate
  /// fits better than the anchor (>= 1); a better fit moves the anchor and restarts them.
  double radius_growth = 1.5;
  double max_radius = 10.0;  ///< map metres: the radius stops growing here (>= initial_radius)
  /// Recovering scans after which a filter that knows its free space restarts global
  /// localization (>= 1); without free space it keeps recovering at max_radius.
  int max_recovery_scans = 40;
};

/// Throws InputError naming `recovery.<field>` when an option is out of range.
void validate(const RecoveryOptions& options);

/// Why a filter was declared diverged.
enum class DivergenceReason {
  none,             ///< not diverged
  low_likelihood,   ///< max_bad_scans consecutive scans below min_beam_likelihood
  spread,           ///< position spread above max_position_std after having converged
  likelihood_drop,  ///< w_fast / w_slow below min_fast_slow_ratio after having converged
};

/// A short name of `reason` ("none", "low_likelihood", "spread", "likelihood_drop").
std::string_view to_string(DivergenceReason reason);

/// The divergence signals of one scan.
struct DivergenceCheck {
  DivergenceReason reason = DivergenceReason::none;  ///< the first signal that fired, or none
  int bad_scans = 0;                                 ///< consecutive bad scans, this one included
  double fast_slow_ratio = 1.0;                      ///< w_fast / w_slow (1 before any scan)
  /// Share of particles augmented MCL would replace: clamp(1 - ratio, 0, max_augmented_fraction).
  double augmented_fraction = 0.0;
  bool diverged() const { return reason != DivergenceReason::none; }  ///< any signal fired
};

/// Tracks the divergence signals over scans. The average likelihood of augmented MCL is the
/// mean beam likelihood at the mean pose (in [0, 1] whatever the beam count or the model's
/// log-likelihood scale, where the product of a scan's beam likelihoods over- and underflows
/// and swings with every beam); both averages start at the first scan's value.
class DivergenceMonitor {
 public:
  /// A monitor that has seen no scan. Validates `options`.
  explicit DivergenceMonitor(const RecoveryOptions& options = {});

  /// Feeds one scan; `has_converged`: whether the filter has been converged since it was
  /// (re)initialized or recovered, which arms the spread and ratio signals.
  const DivergenceCheck& update(double mean_beam_likelihood, const PoseEstimate& estimate,
                                bool has_converged);
  /// The last scan's signals.
  const DivergenceCheck& last() const { return last_; }
  /// Forgets every scan: the bad-scan count and the averages (after a (re)initialization, a
  /// divergence, or on convergence, so that w_slow starts from a converged fit).
  void reset();
  /// The options.
  const RecoveryOptions& options() const { return options_; }

 private:
  RecoveryOptions options_;
  DivergenceCheck last_;
  double w_slow_ = 0.0;
  double w_fast_ = 0.0;
  bool has_average_ = false;
};

}  // namespace floorgrid
