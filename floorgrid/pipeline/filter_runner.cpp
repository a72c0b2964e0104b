#include "floorgrid/pipeline/filter_runner.hpp"

#include <cmath>
#include <utility>

#include "floorgrid/robot/motion_model.hpp"

namespace floorgrid {

ScanMatch match_with(const WallField& walls, const ScanObservation& points, const Pose2& pose,
                     double scale, const ScanMatchOptions& options, const GridRayCaster* caster,
                     double tolerance) {
  return caster ? match_scan(walls, points, pose, scale, options, *caster, tolerance)
                : match_scan(walls, points, pose, scale, options);
}

ScanMatch apply_proposal(ParticleFilter& filter, const WallField& walls,
                         const ScanObservation& points, const ScanMatchOptions& options,
                         const GridRayCaster* caster, double tolerance) {
  const PoseEstimate predicted = estimate_pose(filter.particles());
  const ScanMatch m =
      match_with(walls, points, predicted.pose, predicted.scale, options, caster, tolerance);
  if (!m.ok() && m.failure != ScanMatchFailure::degenerate)
    return m;
  Pose2 to = m.pose;
  if (!m.ok()) {
    // Along a corridor the match only drifted: the cloud keeps its own position there.
    Eigen::Vector2d step = m.pose.translation() - predicted.pose.translation();
    step -= step.dot(m.weak_direction) * m.weak_direction;
    to.x = predicted.pose.x + step.x();
    to.y = predicted.pose.y + step.y();
  }
  filter.shift(predicted.pose, to);
  return m;
}

FilterRunner::FilterRunner(ParticleFilter filter, const ObservationModel& model,
                           const WallField& walls, const RobotLog& log,
                           const ObservationOptions& observation,
                           const FilterRunnerOptions& options, const GridRayCaster* caster)
    : filter_(std::move(filter)),
      model_(model),
      walls_(walls),
      log_(log),
      observation_(observation),
      options_(options),
      caster_(caster) {
  validate(options_.match);
}

std::optional<OdometryMotion> FilterRunner::guided_motion(std::size_t from, std::size_t to) const {
  if (to >= guide_.size() || !guide_[from] || !guide_[to])
    return std::nullopt;
  const Pose2 odometry = log_.scans[from].robot_pose.between(log_.scans[to].robot_pose);
  const Pose2 guided = guide_[from]->between(*guide_[to]);
  const double step = odometry.translation().norm();
  if (step < options_.guide_min_translation &&
      std::abs(odometry.theta) < options_.guide_min_rotation)
    return std::nullopt;
  const double off = (guided.translation() - odometry.translation()).norm();
  const double turned = std::abs(normalize_angle(guided.theta - odometry.theta));
  if (off > options_.guide_max_translation + options_.guide_translation_share * step ||
      turned > options_.guide_max_rotation + options_.guide_rotation_per_metre * step +
                   options_.guide_rotation_share * std::abs(odometry.theta))
    return std::nullopt;
  return odometry_motion(*guide_[from], *guide_[to]);
}

FilterRecord FilterRunner::step(std::size_t i) {
  OdometryMotion motion;
  bool update = true;
  bool guided = false;  // the motion is the guide's
  if (last_) {
    motion = odometry_motion(log_.scans[*last_].robot_pose, log_.scans[i].robot_pose);
    moved_ += std::abs(motion.trans);
    turned_ += std::abs(motion.rot1) + std::abs(motion.rot2);
    update = moved_ >= options_.update_min_translation || turned_ >= options_.update_min_rotation;
    if (const std::optional<OdometryMotion> g = guided_motion(*last_, i)) {
      motion = *g;
      guided = true;
    }
  }
  last_ = i;
  FilterRecord record;
  if (!filter_.initialized())
    return record;
  guided_steps_ += guided;
  const auto predict = [&] {
    if (guided)
      filter_.predict(motion, options_.guided_noise);
    else
      filter_.predict(motion);
  };
  std::optional<ScanMatch> proposal;  // the improved proposal's match of this scan
  if (update) {
    moved_ = turned_ = 0.0;
    const bool tracking = filter_.converged() && filter_.state() == FilterState::tracking;
    const ScanObservation scan = make_observation(log_.scans[i], observation_);
    FilterStatus status;
    if (options_.improved_proposal && tracking) {
      predict();
      const ScanObservation points = make_observation(log_.scans[i], options_.match_observation);
      proposal =
          apply_proposal(filter_, walls_, points, options_.match, caster_, options_.beam_tolerance);
      corrections_ += proposal->ok() || proposal->failure == ScanMatchFailure::degenerate;
      status = filter_.step(OdometryMotion{}, scan, model_, options_.threads);
    } else {
      // A guided motion is predicted with its own noise first; the step then only weighs.
      if (guided)
        predict();
      status = filter_.step(guided ? OdometryMotion{} : motion, scan, model_, options_.threads);
    }
    evaluations_ += filter_.particles().size() * scan.size();
    record.updated = true;
    record.diverged = status.state == FilterState::diverged;
  } else {
    predict();
  }
  const FilterStatus& status = filter_.status();
  record.state = filter_.state();
  record.converged = filter_.converged();
  record.estimate = status.estimate;
  record.check = status.convergence;
  record.fit = status.mean_beam_likelihood;
  const PoseEstimate now = estimate_pose(filter_.particles());
  record.pose = now.pose;
  if (options_.refine && record.converged && proposal) {
    // The proposal matched this very scan: its pose is the refined one.
    record.match = *proposal;
    record.matched = true;
  } else if (options_.refine && record.converged) {
    const ScanObservation points = make_observation(log_.scans[i], options_.match_observation);
    record.match = match_with(walls_, points, now.pose, now.scale, options_.match, caster_,
                              options_.beam_tolerance);
    record.matched = true;
  } else {
    record.match.failure = ScanMatchFailure::too_few_inliers;
  }
  return record;
}

}  // namespace floorgrid
