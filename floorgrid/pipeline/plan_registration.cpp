#include "floorgrid/pipeline/plan_registration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_set>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"

namespace floorgrid {

ScanObservation build_submap(const RobotLog& log, std::span<const std::size_t> scans,
                             std::span<const Pose2> poses, const Pose2& origin,
                             const SubmapOptions& options) {
  if (!(options.bin > 0.0))
    throw InputError("must be > 0", {}, 0, "submap.bin");
  if (scans.size() != poses.size())
    throw InputError("needs one pose per scan", {}, 0, "submap.poses");
  std::unordered_set<std::uint64_t> bins;
  std::vector<Eigen::Vector2d> points;
  const Pose2 origin_inverse = origin.inverse();
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const LaserScan& scan = log.scans.at(scans[k]);
    const Pose2 robot_in_origin = origin_inverse.compose(poses[k]);
    const Pose2 laser_in_robot = scan.robot_pose.between(scan.laser_pose);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      if (!scan.is_return(i) || scan.ranges[i] > options.max_range)
        continue;
      const double a = laser_in_robot.theta + scan.angle(i);
      const Eigen::Vector2d in_robot =
          laser_in_robot.translation() + scan.ranges[i] * Eigen::Vector2d(std::cos(a), std::sin(a));
      const Eigen::Vector2d p = robot_in_origin.transform(in_robot);
      const auto bx = static_cast<std::int64_t>(std::floor(p.x() / options.bin));
      const auto by = static_cast<std::int64_t>(std::floor(p.y() / options.bin));
      const std::uint64_t key =
          (static_cast<std::uint64_t>(bx) << 32) ^ (static_cast<std::uint64_t>(by) & 0xffffffffULL);
      if (bins.insert(key).second)
        points.push_back(p);
    }
  }
  ScanObservation cloud;
  const std::size_t keep = std::min(points.size(), std::max<std::size_t>(1, options.max_points));
  for (std::size_t k = 0; k < keep; ++k) {
    const Eigen::Vector2d& p = points[k * points.size() / keep];  // evenly thinned
    cloud.angle.push_back(static_cast<float>(std::atan2(p.y(), p.x())));
    cloud.range.push_back(static_cast<float>(p.norm()));
    cloud.end_x.push_back(static_cast<float>(p.x()));
    cloud.end_y.push_back(static_cast<float>(p.y()));
    cloud.beam.push_back(static_cast<int>(k));
  }
  return cloud;
}

Pose2 PlanRegistration::plan_pose(const Pose2& pose_in_map) const {
  if (warp_)
    return warp_->apply(pose_in_map);
  const Pose2 relative = origin_in_map_.between(pose_in_map);  // world metres
  return origin_in_plan_.compose({relative.x / scale_, relative.y / scale_, relative.theta});
}

Pose2 PlanRegistration::map_pose(const Pose2& pose_in_plan) const {
  if (warp_)
    return warp_->inverse(pose_in_plan);
  const Pose2 relative = origin_in_plan_.between(pose_in_plan);  // plan metres
  return origin_in_map_.compose({relative.x * scale_, relative.y * scale_, relative.theta});
}

void LocalRegistration::add(std::size_t scan, const Pose2& pose_in_map, const Pose2& pose_in_plan) {
  const Pair pair{scan, pose_in_map, pose_in_plan};
  if (pairs_.size() < window_) {
    pairs_.push_back(pair);
  } else {
    pairs_[next_] = pair;
    next_ = (next_ + 1) % window_;
  }
  refit();
}

double LocalRegistration::distance_to(const Pose2& pose_in_map) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Pair& p : pairs_)
    nearest = std::min(nearest, (p.map.translation() - pose_in_map.translation()).norm());
  return nearest;
}

bool LocalRegistration::fresh(std::size_t scan, std::size_t min_pairs, std::size_t max_age) const {
  if (pairs_.size() < std::max<std::size_t>(1, min_pairs))
    return false;
  std::size_t newest = 0;
  for (const Pair& p : pairs_)
    newest = std::max(newest, p.scan);
  return scan <= newest + max_age;
}

void LocalRegistration::clear() {
  pairs_.clear();
  next_ = 0;
}

void LocalRegistration::refit() {
  // Heading offset: the circular mean of the pairs' heading differences (the positions of a
  // short window are nearly collinear and cannot fix a rotation); translation from centroids.
  double s = 0.0, c = 0.0;
  Eigen::Vector2d map_centroid = Eigen::Vector2d::Zero(), plan_centroid = Eigen::Vector2d::Zero();
  for (const Pair& p : pairs_) {
    const double d = normalize_angle(p.plan.theta - p.map.theta);
    s += std::sin(d);
    c += std::cos(d);
    map_centroid += p.map.translation() / scale_;
    plan_centroid += p.plan.translation();
  }
  const double k = static_cast<double>(pairs_.size());
  const double rotation = std::atan2(s, c);
  const Eigen::Vector2d t = plan_centroid / k - rotation_2d(rotation) * (map_centroid / k);
  offset_ = {t.x(), t.y(), rotation};
}

Pose2 LocalRegistration::plan_pose(const Pose2& pose_in_map) const {
  const Eigen::Vector2d p = offset_.transform(pose_in_map.translation() / scale_);
  return {p.x(), p.y(), normalize_angle(pose_in_map.theta + offset_.theta)};
}

Pose2 LocalRegistration::map_pose(const Pose2& pose_in_plan) const {
  const Eigen::Vector2d m = offset_.inverse().transform(pose_in_plan.translation()) * scale_;
  return {m.x(), m.y(), normalize_angle(pose_in_plan.theta - offset_.theta)};
}

ScanObservation thin(const ScanObservation& cloud, std::size_t points) {
  ScanObservation thinned;
  const std::size_t keep = std::min(cloud.size(), std::max<std::size_t>(1, points));
  for (std::size_t k = 0; k < keep; ++k) {
    const std::size_t j = k * cloud.size() / keep;
    thinned.push_back_beam(cloud, j);
  }
  return thinned;
}

namespace {

/// Each seeded hypothesis and its neighbours half a lattice step away in every dimension.
ParticleSet half_step_neighbours(const HypothesisSeeding& seeds, double heading_step,
                                 double scale_step, double min_scale) {
  const double step = seeds.position_step;
  const ParticleSet& p = seeds.particles;
  const bool with_scale = p.has_scale();
  ParticleSet candidates;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dt = -1; dt <= 1; ++dt)
          for (int ds = with_scale ? -1 : 0; ds <= (with_scale ? 1 : 0); ++ds) {
            candidates.x.push_back(p.x[i] + 0.5 * dx * step);
            candidates.y.push_back(p.y[i] + 0.5 * dy * step);
            candidates.theta.push_back(normalize_angle(p.theta[i] + 0.5 * dt * heading_step));
            if (with_scale)
              candidates.scale.push_back(std::max(min_scale, p.scale[i] + 0.5 * ds * scale_step));
          }
  }
  return candidates;
}

/// The best-scoring candidate and the score of the best one clearly elsewhere.
std::pair<std::size_t, double> best_and_runner_up(const ParticleSet& candidates,
                                                  const std::vector<double>& score,
                                                  const PlanRegistrationOptions& options) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < score.size(); ++i)
    if (score[i] > score[best])
      best = i;
  double runner_up = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < score.size(); ++i) {
    const double distance =
        std::hypot(candidates.x[i] - candidates.x[best], candidates.y[i] - candidates.y[best]);
    const double turn = std::abs(normalize_angle(candidates.theta[i] - candidates.theta[best]));
    if ((distance > options.runner_up_distance || turn > options.runner_up_heading) &&
        score[i] > runner_up)
      runner_up = score[i];
  }
  return {best, runner_up};
}

}  // namespace

PlanRegistrationResult register_on_plan(const OccupancyGrid& plan, const ObservationModel& model,
                                        const ScanObservation& submap, const Pose2& submap_origin,
                                        const std::optional<ScaleRange>& scales, double scale,
                                        const PlanRegistrationOptions& options, int threads) {
  if (submap.size() == 0)
    throw InputError("the run gave no laser endpoints to locate on the plan", {}, 0, "log");
  ScanObservation cloud = submap;
  if (!scales) {
    // A known scale: the cloud in plan metres, hypotheses without a scale of their own.
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      cloud.end_x[i] = static_cast<float>(cloud.end_x[i] / scale);
      cloud.end_y[i] = static_cast<float>(cloud.end_y[i] / scale);
    }
  }
  // Coarse: the lattice on a thinned cloud.
  const FreeSpaceSampler free_space(plan);
  Random random(options.seed);
  const HypothesisSeeding seeds =
      seed_best_hypotheses(free_space, thin(cloud, options.coarse_points), model, options.seeding,
                           scales, random, threads);
  // Fine: each kept hypothesis and its half-step neighbours, scored with every point.
  const double heading_step = 2.0 * std::numbers::pi / std::max(1, options.seeding.headings);
  const double scale_step =
      scales ? (scales->max - scales->min) / std::max(1, options.seeding.scales) : 0.0;
  const ParticleSet candidates =
      half_step_neighbours(seeds, heading_step, scale_step, options.min_scale);
  std::vector<double> score;
  model.log_likelihood(cloud, candidates, score, threads);
  if (candidates.size() == 0)
    throw InputError("the plan has no free space to locate the run in", {}, 0, "floorplan");
  const auto [best, runner_up] = best_and_runner_up(candidates, score, options);
  PlanRegistrationResult result;
  result.hypotheses = seeds.scored + candidates.size();
  result.points = cloud.size();
  result.registration = PlanRegistration(submap_origin, candidates.pose(best),
                                         candidates.has_scale() ? candidates.scale[best] : scale);
  result.log_likelihood = score[best];
  result.runner_up_log_likelihood = runner_up;
  return result;
}

}  // namespace floorgrid
