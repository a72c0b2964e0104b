#include "floorgrid/localization/particle_filter.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/localization/resampling.hpp"

namespace floorgrid {
namespace {

// Scales are kept above this (a scale is a ratio of lengths).
constexpr double kMinScale = 1e-6;

// Below this sum the direct products w_i exp(ll_i - max) lose precision (subnormals) or their
// reciprocal overflows; the log domain takes over.
constexpr double kMinRepresentableTotal = 1e-200;

bool non_negative(double v) {
  return v >= 0.0 && std::isfinite(v);
}

// A log-likelihood the update can use: NaN and +inf (model bugs) count as impossible.
double usable(double log_likelihood) {
  return log_likelihood < std::numeric_limits<double>::infinity()
             ? log_likelihood
             : -std::numeric_limits<double>::infinity();
}

std::size_t share_of(double fraction, std::size_t count) {
  return static_cast<std::size_t>(std::llround(fraction * static_cast<double>(count)));
}

}  // namespace

void validate(const ParticleFilterOptions& o) {
  require_option(non_negative(o.motion.alpha1), "particle_filter", "motion.alpha1", o.motion.alpha1,
                 ">= 0");
  require_option(non_negative(o.motion.alpha2), "particle_filter", "motion.alpha2", o.motion.alpha2,
                 ">= 0");
  require_option(non_negative(o.motion.alpha3), "particle_filter", "motion.alpha3", o.motion.alpha3,
                 ">= 0");
  require_option(non_negative(o.motion.alpha4), "particle_filter", "motion.alpha4", o.motion.alpha4,
                 ">= 0");
  require_option(non_negative(o.scale_walk), "particle_filter", "scale_walk", o.scale_walk, ">= 0");
  require_option(o.tracking_particles >= 1, "particle_filter", "tracking_particles",
                 o.tracking_particles, ">= 1");
  require_option(o.global_particles >= 1, "particle_filter", "global_particles", o.global_particles,
                 ">= 1");
  require_option(o.resample_ess_ratio >= 0.0 && o.resample_ess_ratio <= 1.0, "particle_filter",
                 "resample_ess_ratio", o.resample_ess_ratio, "in [0, 1]");
  validate(o.free_space);
  validate(o.seeding);
  validate(o.convergence);
  validate(o.recovery);
}

std::string_view to_string(FilterState state) {
  switch (state) {
    case FilterState::uninitialized:
      return "uninitialized";
    case FilterState::global:
      return "global";
    case FilterState::tracking:
      return "tracking";
    case FilterState::diverged:
      return "diverged";
    case FilterState::recovering:
      return "recovering";
  }
  return "uninitialized";
}

void predict_particles(ParticleSet& particles, const OdometryMotion& motion_in_world,
                       const MotionNoise& noise, double scale_walk, Random& random) {
  const std::size_t n = particles.size();
  const bool walk = scale_walk > 0.0 && particles.has_scale();
  const double walk_sigma = scale_walk * std::sqrt(std::abs(motion_in_world.trans));
  for (std::size_t i = 0; i < n; ++i) {
    OdometryMotion m = sample_noisy_motion(motion_in_world, noise, random);
    m.trans /= particles.scale_of(i);  // world metres to this particle's map metres
    const Pose2 moved = apply_motion(particles.pose(i), m);
    particles.x[i] = moved.x;
    particles.y[i] = moved.y;
    particles.theta[i] = moved.theta;
    if (walk)
      particles.scale[i] = std::max(kMinScale, particles.scale[i] + random.normal(walk_sigma));
  }
}

bool update_weights(ParticleSet& particles, std::span<const double> log_likelihood) {
  const std::size_t n = particles.size();
  assert(log_likelihood.size() == n);
  if (particles.weight.size() != n)
    particles.weight.assign(n, n > 0 ? 1.0 / static_cast<double>(n) : 0.0);
  std::vector<double>& w = particles.weight;

  double max_ll = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    if (w[i] > 0.0)
      max_ll = std::max(max_ll, usable(log_likelihood[i]));
  }
  if (!std::isfinite(max_ll))
    return false;
  // Usually w_i exp(ll_i - max) sums to something representable: two passes, no logarithms.
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    total += w[i] * std::exp(usable(log_likelihood[i]) - max_ll);
  if (total > kMinRepresentableTotal && std::isfinite(total)) {
    const double inverse = 1.0 / total;
    for (std::size_t i = 0; i < n; ++i)
      w[i] *= std::exp(usable(log_likelihood[i]) - max_ll) * inverse;
    return true;
  }
  // It underflows when the likeliest particles carry tiny weights: add in the log domain.
  double max_lw = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    max_lw = std::max(max_lw, std::log(w[i]) + usable(log_likelihood[i]));
  total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    w[i] = std::exp(std::log(w[i]) + usable(log_likelihood[i]) - max_lw);
    total += w[i];
  }
  for (double& wi : w)
    wi /= total;
  return true;
}

ParticleFilter::ParticleFilter(const ParticleFilterOptions& options, std::uint64_t seed)
    : options_(options),
      random_(seed),
      convergence_(options.convergence),
      divergence_(options.recovery) {
  validate(options_);
}

void ParticleFilter::start(ParticleSet particles, FilterState state) {
  particles_ = std::move(particles);
  state_ = state;
  convergence_.reset();
  divergence_.reset();
  has_converged_ = false;
  recovery_scans_ = 0;
  status_ = {};
  status_.state = state;
  status_.scan = scans_;
  status_.estimate = estimate_pose(particles_);
  status_.particles = particles_.size();
}

void ParticleFilter::initialize_tracking(const TrackingStart& start_pose) {
  validate(start_pose);
  free_space_.reset();
  scale_range_.reset();
  if (start_pose.scale) {
    const double s = *start_pose.scale, spread = 3.0 * start_pose.scale_sigma;
    scale_range_ = ScaleRange{std::max(kMinScale, s - spread), s + spread};
  }
  scans_ = 0;
  start(sample_tracking_start(start_pose, options_.tracking_particles, random_),
        FilterState::tracking);
  anchor_ = start_pose.pose;
  anchor_scale_ = start_pose.scale.value_or(1.0);
  anchor_scale_std_ = start_pose.scale_sigma;
}

void ParticleFilter::initialize_tracking(const TrackingStart& start_pose,
                                         const OccupancyGrid& free_space) {
  FreeSpaceSampler sampler(free_space, options_.free_space);
  initialize_tracking(start_pose);
  free_space_.emplace(std::move(sampler));
}

void ParticleFilter::initialize_global(const OccupancyGrid& free_space,
                                       const std::optional<ScaleRange>& scales) {
  if (scales)
    validate(*scales);
  free_space_.emplace(free_space, options_.free_space);
  scale_range_ = scales;
  scans_ = 0;
  start(sample_global(*free_space_, options_.global_particles, scales, random_),
        FilterState::global);
  anchor_.reset();
}

HypothesisSeeding ParticleFilter::initialize_from_hypotheses(
    const OccupancyGrid& free_space, const ScanObservation& first_scan,
    const ObservationModel& model, const std::optional<ScaleRange>& scales, int threads) {
  if (scales)
    validate(*scales);
  free_space_.emplace(free_space, options_.free_space);
  scale_range_ = scales;
  HypothesisSeeding seeding = seed_best_hypotheses(*free_space_, first_scan, model,
                                                   options_.seeding, scales, random_, threads);
  scans_ = 0;
  start(seeding.particles, FilterState::global);
  anchor_.reset();
  return seeding;
}

void ParticleFilter::restart_global() {
  start(sample_global(*free_space_, options_.global_particles, scale_range_, random_),
        FilterState::global);
  anchor_.reset();
}

void ParticleFilter::predict(const OdometryMotion& motion_in_world) {
  predict(motion_in_world, options_.motion);
}

void ParticleFilter::predict(const OdometryMotion& motion_in_world, const MotionNoise& noise) {
  predict_particles(particles_, motion_in_world, noise, options_.scale_walk, random_);
  if (anchor_) {
    OdometryMotion m = motion_in_world;
    m.trans /= anchor_scale_;
    anchor_ = apply_motion(*anchor_, m);
  }
}

void ParticleFilter::shift(const Pose2& from, const Pose2& to) {
  const Pose2 delta = to.compose(from.inverse());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Pose2 moved = delta.compose(particles_.pose(i));
    particles_.x[i] = moved.x;
    particles_.y[i] = moved.y;
    particles_.theta[i] = moved.theta;
  }
  if (anchor_)
    anchor_ = delta.compose(*anchor_);
}

bool ParticleFilter::update(const ScanObservation& scan, const ObservationModel& model,
                            int threads) {
  model.log_likelihood(scan, particles_, log_likelihood_, threads);
  assert(log_likelihood_.size() == particles_.size());
  if (log_likelihood_.size() != particles_.size())
    return false;
  return update_weights(particles_, log_likelihood_);
}

void ParticleFilter::update_anchor(const PoseEstimate& estimate) {
  anchor_ = estimate.pose;
  anchor_scale_ = estimate.scale;
  anchor_scale_std_ = estimate.scale_std;
}

void ParticleFilter::inject(std::size_t begin, std::size_t global_count, std::size_t end,
                            double radius, double heading_spread) {
  const std::size_t middle = begin + global_count;
  if (global_count > 0)
    sample_free_space_particles(*free_space_, scale_range_, random_, scratch_, begin, middle);
  if (middle < end)
    sample_disc_particles(*anchor_, radius, heading_spread, anchor_scale_, anchor_scale_std_,
                          random_, scratch_, middle, end);
}

void ParticleFilter::resample(std::size_t count, std::size_t global_count, std::size_t local_count,
                              double radius, double heading_spread) {
  const std::size_t injected = global_count + local_count;
  assert(injected <= count);
  low_variance_resample(particles_.weight, count - injected, random_, indices_);
  gather_particles(particles_, indices_, scratch_);
  scratch_.x.resize(count);
  scratch_.y.resize(count);
  scratch_.theta.resize(count);
  scratch_.scale.resize(particles_.has_scale() ? count : 0);
  scratch_.weight.assign(count, 1.0 / static_cast<double>(count));
  inject(count - injected, global_count, count, radius, heading_spread);
  std::swap(particles_, scratch_);
}

FilterStatus ParticleFilter::step(const OdometryMotion& motion_in_world,
                                  const ScanObservation& scan, const ObservationModel& model,
                                  int threads) {
  if (!initialized())
    throw std::logic_error("ParticleFilter::step called before initialization");
  predict(motion_in_world);
  FilterStatus status;
  status.update_ok = update(scan, model, threads);
  status.scan = ++scans_;
  status.estimate = estimate_pose(particles_);
  status.mean_beam_likelihood =
      model.mean_beam_likelihood(scan, status.estimate.pose, status.estimate.scale);
  status.convergence =
      convergence_.update(status.estimate, status.mean_beam_likelihood, particles_.has_scale());
  status.divergence =
      divergence_.update(status.mean_beam_likelihood, status.estimate, has_converged_);

  const RecoveryOptions& r = options_.recovery;
  std::size_t count = particles_.size();
  std::size_t global_count = 0, local_count = 0;
  double radius = r.max_radius, heading_spread = std::numbers::pi;
  bool diverged_now = false;
  // Recovery's injection: a share over the free space when known, the rest on a disc around
  // the anchor whose radius (and heading spread) grows with every scan that finds no better fit.
  auto plan_recovery = [&]() {
    const double growth = std::pow(r.radius_growth, anchor_age_);
    radius = std::min(r.max_radius, r.initial_radius * growth);
    heading_spread = std::min(std::numbers::pi, r.initial_heading_spread * growth);
    const std::size_t n =
        std::min(count, std::max<std::size_t>(1, share_of(r.recovery_fraction, count)));
    global_count = free_space_ ? share_of(r.global_share, n) : 0;
    local_count = n - global_count;
  };
  // Converged (again): tracking with the tracking count.
  auto becomes_converged = [&]() {
    state_ = FilterState::tracking;
    has_converged_ = true;
    divergence_.reset();  // w_slow starts from a converged fit
    count = options_.tracking_particles;
  };
  auto enter_recovery = [&]() {
    diverged_now = true;
    state_ = FilterState::recovering;
    has_converged_ = false;
    convergence_.reset();
    divergence_.reset();
    recovery_scans_ = 0;
    if (!anchor_)
      update_anchor(status.estimate);
    // The anchor stays the last good estimate; any later estimate that fits better than the
    // lost one re-centres it.
    anchor_fit_ = std::isnan(status.mean_beam_likelihood) ? 0.0 : status.mean_beam_likelihood;
    anchor_age_ = 0;
    plan_recovery();
  };

  switch (state_) {
    case FilterState::global:
      if (convergence_.converged()) {
        becomes_converged();
      } else if (r.enabled && status.divergence.reason == DivergenceReason::low_likelihood &&
                 status.convergence.position_ok && status.convergence.heading_ok) {
        // The cloud has collapsed onto one pose that has not fitted for max_bad_scans scans:
        // depletion left it on the few particles that happened to lie near the truth, and
        // nothing but the motion noise would move it. Search around it like a lost filter.
        enter_recovery();
      }
      break;
    case FilterState::tracking:
    case FilterState::diverged:
      if (convergence_.converged() && !has_converged_)
        becomes_converged();
      if (r.enabled && status.divergence.diverged()) {
        enter_recovery();
      } else if (r.enabled && has_converged_ && status.divergence.augmented_fraction > 0.0) {
        // Augmented MCL: fresh particles from the global distribution.
        const std::size_t n = share_of(status.divergence.augmented_fraction, count);
        (free_space_ ? global_count : local_count) = n;
      }
      break;
    case FilterState::recovering:
      if (convergence_.converged()) {
        becomes_converged();
      } else if (++recovery_scans_ >= r.max_recovery_scans && free_space_) {
        restart_global();
        status.restarted_global = true;
      } else {
        // A better fit than the anchor's re-centres the search there with the initial radius
        // (refining what the wide search found); otherwise the radius keeps growing.
        if (status.mean_beam_likelihood > anchor_fit_) {
          update_anchor(status.estimate);
          anchor_fit_ = status.mean_beam_likelihood;
          anchor_age_ = 0;
        } else {
          ++anchor_age_;
        }
        plan_recovery();
      }
      break;
    case FilterState::uninitialized:
      break;
  }
  if (state_ == FilterState::tracking && convergence_.converged())
    update_anchor(status.estimate);

  if (!status.restarted_global) {
    status.injected = global_count + local_count;
    status.resampled = status.estimate.ess_ratio < options_.resample_ess_ratio ||
                       count != particles_.size() || status.injected > 0;
    if (status.resampled)
      resample(count, global_count, local_count, radius, heading_spread);
  }
  status.state = diverged_now ? FilterState::diverged : state_;
  status.converged = state_ == FilterState::tracking && convergence_.converged();
  status.particles = particles_.size();
  status_ = status;
  return status;
}

}  // namespace floorgrid
