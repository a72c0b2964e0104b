#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/localization/convergence.hpp"
#include "floorgrid/localization/divergence.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/localization/particle_initialization.hpp"
#include "floorgrid/localization/particles.hpp"
#include "floorgrid/localization/pose_estimate.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/robot/motion_model.hpp"

namespace floorgrid {

/// Options of one Monte Carlo localization filter on one map; every default lives here or in
/// the nested structs.
struct ParticleFilterOptions {
  MotionNoise motion;  ///< odometry noise alpha1..alpha4 (world metres and radians)
  /// Random walk of the particles' scales, per square root of a world metre travelled: each
  /// motion adds N(0, scale_walk^2 |trans|) to every scale (a variance growing with the distance,
  /// whatever the step length); 0 freezes the scales. Lets the plan's scale search keep
  /// exploring. Only for particles that carry a scale.
  double scale_walk = 0.0;
  std::size_t tracking_particles = 2000;  ///< particles while tracking (>= 1)
  /// Particles of global localization (uniform start and global restarts; >= 1): the filter
  /// shrinks to tracking_particles at the resampling of the scan on which it converges.
  std::size_t global_particles = 50000;
  /// Resample when N_eff / N falls below this, in [0, 1] (1: every scan; 0: only when the
  /// particle count changes or particles are injected).
  double resample_ess_ratio = 0.5;
  FreeSpaceOptions free_space;       ///< which free cells global sampling and injection use
  HypothesisSeedingOptions seeding;  ///< initialize_from_hypotheses
  ConvergenceOptions convergence;    ///< when the filter counts as converged
  RecoveryOptions recovery;          ///< divergence detection and recovery
};

/// Throws InputError naming the field (`particle_filter.<field>`, `convergence.<field>`, ...)
/// when an option is out of range.
void validate(const ParticleFilterOptions& options);

/// Where a filter is in its life:
///
///   uninitialized --initialize_global / initialize_from_hypotheses--> global
///   uninitialized --initialize_tracking--> tracking
///   global --converged--> tracking (the particles shrink to tracking_particles)
///   global --the cloud collapsed onto one pose that fits badly for max_bad_scans scans--> diverged
///   tracking --a divergence signal (RecoveryOptions)--> diverged
///   diverged --> recovering (diverged is reported for the one scan that detected it)
///   recovering --converged--> tracking (shrinking to tracking_particles)
///   recovering --max_recovery_scans, free space known--> global (restart, global_particles)
///
/// While recovering, every scan replaces recovery_fraction of the particles: a global_share
/// over the free space (when known) and the rest on a disc around the anchor, the last good
/// estimate carried along by the odometry. The disc grows (radius_growth per scan) while no
/// estimate fits better than the anchor; an estimate that does becomes the anchor and the disc
/// restarts small, so a wide search that finds the pose roughly then refines it. While
/// tracking after convergence, augmented MCL injects particles from the global distribution.
enum class FilterState {
  uninitialized,  ///< no particles yet
  global,         ///< global localization: no pose known yet
  tracking,       ///< following one pose hypothesis (converged or about to be)
  diverged,       ///< lost on this scan (a status only: the filter is recovering from now on)
  recovering,     ///< re-localizing after a divergence
};

/// A short name of `state` ("uninitialized", "global", "tracking", "diverged", "recovering").
std::string_view to_string(FilterState state);

/// What one filter step did and where it left the filter. The estimate, the beam likelihood and
/// the checks describe the weighted particles after this scan's update (before resampling).
struct FilterStatus {
  FilterState state = FilterState::uninitialized;  ///< after this step (diverged: lost on it)
  /// Whether the filter counts as converged after this step (ConvergenceOptions, with its
  /// hysteresis) and is tracking: pairs may be made from this scan when true.
  bool converged = false;
  std::size_t scan = 0;   ///< steps since the last initialization, this one included
  PoseEstimate estimate;  ///< mean pose, spread, N_eff / N
  /// The model's mean beam likelihood at the mean pose and scale, in [0, 1].
  double mean_beam_likelihood = 0.0;
  ConvergenceCheck convergence;  ///< this scan's convergence criteria
  DivergenceCheck divergence;    ///< this scan's divergence signals (why, when diverged)
  /// False when no particle had a finite log-likelihood: the weights were left unchanged.
  bool update_ok = true;
  bool resampled = false;         ///< whether the particles were resampled
  std::size_t injected = 0;       ///< particles replaced by fresh samples (augmented MCL, recovery)
  bool restarted_global = false;  ///< recovery gave up and restarted global localization
  std::size_t particles = 0;      ///< particles after this step
};

/// Moves every particle by a noisy sample of `motion_in_world` (the odometry model with
/// alpha1..alpha4, noise in world metres); particle i's translation is divided by its scale
/// (its map metre is scale world metres). With `scale_walk` > 0, each scale then takes a
/// random-walk step N(0, scale_walk^2 |motion.trans|), kept > 0. O(N), deterministic for
/// `random`'s state.
void predict_particles(ParticleSet& particles, const OdometryMotion& motion_in_world,
                       const MotionNoise& noise, double scale_walk, Random& random);

/// The measurement update: w_i <- w_i exp(ll_i - max_j ll_j), normalized to sum 1 (log-sum-exp:
/// no underflow however negative the log-likelihoods; equal weights assumed when the set has
/// none). NaN or +inf log-likelihoods count as -inf. Returns false, leaving the weights
/// unchanged, when no particle with weight has a finite log-likelihood.
bool update_weights(ParticleSet& particles, std::span<const double> log_likelihood);

/// Monte Carlo localization on one map (thesis 3.5.4): odometry motion model, an observation
/// model, low-variance resampling when N_eff / N drops, the weighted mean pose (eq. 4.24-4.26),
/// convergence with hysteresis, and divergence detection with recovery (augmented MCL while
/// tracking, injection around the last good estimate with a growing radius and over the free
/// space after a divergence). All randomness comes from the seed; the result does not depend
/// on the thread count. A step costs O(N) plus the observation model; buffers are reused, so a
/// steady particle count allocates nothing. No I/O.
class ParticleFilter {
 public:
  /// An uninitialized filter. Throws InputError on bad options.
  explicit ParticleFilter(const ParticleFilterOptions& options = {}, std::uint64_t seed = 1);

  /// Starts tracking from a known pose with tracking_particles particles. Without a free space,
  /// recovery injects particles around the anchor only.
  void initialize_tracking(const TrackingStart& start);
  /// Starts tracking; `free_space` (the map's grid) also lets recovery inject particles over it
  /// and restart global localization.
  void initialize_tracking(const TrackingStart& start, const OccupancyGrid& free_space);
  /// Starts global localization: global_particles particles uniform over the free cells of
  /// `free_space` (per options.free_space), uniform headings, and scales uniform over `scales`
  /// when given (none otherwise).
  void initialize_global(const OccupancyGrid& free_space,
                         const std::optional<ScaleRange>& scales = std::nullopt);
  /// Starts global localization from the best hypotheses of `first_scan` (seed_best_hypotheses
  /// with options.seeding): the more reliable global start. The next step() should carry the
  /// motion since `first_scan` and the next scan. Returns what the seeding did.
  HypothesisSeeding initialize_from_hypotheses(
      const OccupancyGrid& free_space, const ScanObservation& first_scan,
      const ObservationModel& model, const std::optional<ScaleRange>& scales = std::nullopt,
      int threads = kDefaultThreads);

  /// The motion step alone (predict_particles with the filter's noise, scale walk and random
  /// source); also carries the anchor along.
  void predict(const OdometryMotion& motion_in_world);
  /// The motion step with `noise` instead of the options' odometry noise: a motion known
  /// better than the odometry's (another filter's poses) is spread by its own noise.
  void predict(const OdometryMotion& motion_in_world, const MotionNoise& noise);
  /// Moves the whole cloud rigidly so that `from` lands on `to` (each particle p becomes
  /// to * from^-1 * p; the anchor moves along): the correction of an improved proposal, which
  /// centres the predicted particles where a scan match puts the robot before they are weighted
  /// (Grisetti, Stachniss, Burgard 2007). Keeps the cloud's spread and weights.
  void shift(const Pose2& from, const Pose2& to);
  /// The measurement step alone (update_weights with `model`'s log-likelihoods); returns
  /// update_weights' result. step() is predict, update, then the assessment and resampling.
  bool update(const ScanObservation& scan, const ObservationModel& model,
              int threads = kDefaultThreads);
  /// One full cycle for one scan: predict by `motion_in_world` (the odometry since the previous
  /// scan, world metres), update with `scan`, estimate, check convergence and divergence, move
  /// through the states, resample (when N_eff / N < resample_ess_ratio, when the particle count
  /// changes, or to inject particles) and inject. Throws std::logic_error when uninitialized.
  FilterStatus step(const OdometryMotion& motion_in_world, const ScanObservation& scan,
                    const ObservationModel& model, int threads = kDefaultThreads);

  /// The particles (after the last step's resampling).
  const ParticleSet& particles() const { return particles_; }
  /// The last step's estimate (of the particles before resampling), or of the initial
  /// particles before any step.
  const PoseEstimate& estimate() const { return status_.estimate; }
  /// The last step's status.
  const FilterStatus& status() const { return status_; }
  /// The current state (recovering after a step that reported diverged).
  FilterState state() const { return state_; }
  /// Whether the last step left the filter converged (see FilterStatus::converged).
  bool converged() const { return status_.converged; }
  /// Whether an initialize_* call has been made.
  bool initialized() const { return state_ != FilterState::uninitialized; }
  /// The options.
  const ParticleFilterOptions& options() const { return options_; }

 private:
  void start(ParticleSet particles, FilterState state);
  void restart_global();
  void update_anchor(const PoseEstimate& estimate);
  void inject(std::size_t begin, std::size_t global_count, std::size_t end, double radius,
              double heading_spread);
  void resample(std::size_t count, std::size_t global_count, std::size_t local_count, double radius,
                double heading_spread);

  ParticleFilterOptions options_;
  Random random_;
  ParticleSet particles_;
  ParticleSet scratch_;  // resampling target, swapped with particles_
  std::vector<double> log_likelihood_;
  std::vector<std::size_t> indices_;
  std::optional<FreeSpaceSampler> free_space_;
  std::optional<ScaleRange> scale_range_;  // where global samples draw their scales
  ConvergenceMonitor convergence_;
  DivergenceMonitor divergence_;
  FilterState state_ = FilterState::uninitialized;
  FilterStatus status_;
  bool has_converged_ = false;  // converged since the last (re)initialization or divergence
  // The anchor of local recovery: the last good estimate, carried along by the odometry.
  std::optional<Pose2> anchor_;
  double anchor_scale_ = 1.0;
  double anchor_scale_std_ = 0.0;
  double anchor_fit_ = 0.0;  // mean beam likelihood of the anchor while recovering
  int anchor_age_ = 0;       // recovering scans since the anchor last moved to a better fit
  int recovery_scans_ = 0;
  std::size_t scans_ = 0;
};

}  // namespace floorgrid
