#include "floorgrid/pipeline/submap_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "floorgrid/localization/particles.hpp"

namespace floorgrid {

namespace {

/// The log-likelihood of `cloud` at each of `poses` (plan frame) at `scale`.
std::vector<double> scores(const ObservationModel& field, const ScanObservation& cloud,
                           const std::vector<Pose2>& poses, double scale) {
  ParticleSet set;
  for (const Pose2& pose : poses) {
    set.x.push_back(pose.x);
    set.y.push_back(pose.y);
    set.theta.push_back(pose.theta);
  }
  set.scale.assign(poses.size(), scale);
  std::vector<double> out;
  field.log_likelihood(cloud, set, out, 1);
  return out;
}

/// A placement of the submap and its score.
struct Placement {
  Pose2 pose;
  double score = -std::numeric_limits<double>::infinity();
};

/// Climbs from `start` by steps of `step` (plan metres) and `heading_step`, halving both until
/// they are `levels` halvings finer, with every point of `cloud`, only where `inside` holds.
template <typename Inside>
Placement refine(const ObservationModel& field, const ScanObservation& cloud, double scale,
                 Pose2 start, double step, double heading_step, int levels, const Inside& inside) {
  Placement best{start, scores(field, cloud, {start}, scale)[0]};
  for (int level = 0; level < levels;) {
    const Pose2& p = best.pose;
    std::vector<Pose2> around;
    for (const Pose2& q :
         {Pose2{p.x + step, p.y, p.theta}, Pose2{p.x - step, p.y, p.theta},
          Pose2{p.x, p.y + step, p.theta}, Pose2{p.x, p.y - step, p.theta},
          Pose2{p.x, p.y, p.theta + heading_step}, Pose2{p.x, p.y, p.theta - heading_step}}) {
      if (inside(q))
        around.push_back(q);
    }
    const std::vector<double> s =
        around.empty() ? std::vector<double>{} : scores(field, cloud, around, scale);
    const auto top = std::max_element(s.begin(), s.end());
    if (top != s.end() && *top > best.score) {
      best = {around[static_cast<std::size_t>(top - s.begin())], *top};
      continue;
    }
    step /= 2.0;
    heading_step /= 2.0;
    ++level;
  }
  return best;
}

}  // namespace

SubmapCheck::SubmapCheck(const SubmapCheckOptions& options, const RobotLog& log,
                         const ObservationModel& plan_field, double scale)
    : options_(options), log_(log), field_(plan_field), scale_(scale) {}

void SubmapCheck::add(std::size_t scan, const Pose2& grid_pose) {
  if (!options_.enabled)
    return;
  while (!joined_.empty() && joined_.front().scan + options_.window < scan)
    joined_.pop_front();
  if (!joined_.empty()) {
    const Pose2& last = joined_.back().pose;
    if ((grid_pose.translation() - last.translation()).norm() < options_.spacing &&
        std::abs(normalize_angle(grid_pose.theta - last.theta)) < options_.spacing_heading)
      return;
  }
  joined_.push_back({scan, grid_pose});
  if (joined_.size() > options_.max_scans)
    joined_.pop_front();
  ++joined_since_check_;
}

bool SubmapCheck::due(std::size_t scan) const {
  return options_.enabled && joined_since_check_ > 0 && joined_.size() >= options_.min_scans &&
         (!last_check_ || scan >= *last_check_ + options_.every);
}

std::optional<SubmapRelocation> SubmapCheck::check(std::size_t scan, const Pose2& grid_pose,
                                                   const Pose2& plan_pose,
                                                   const Pose2& registered) {
  last_check_ = scan;
  joined_since_check_ = 0;
  const std::optional<SubmapRelocation> found = search(grid_pose, plan_pose, registered);
  if (!found) {
    pending_.reset();
    confirmed_ = 0;
    return std::nullopt;
  }
  const Eigen::Vector2d shift = found->plan_pose.translation() - plan_pose.translation();
  const bool same = pending_ && (shift - *pending_).norm() * scale_ < options_.min_shift;
  confirmed_ = same ? confirmed_ + 1 : 1;
  pending_ = shift;
  if (confirmed_ < options_.confirmations)
    return std::nullopt;
  pending_.reset();
  confirmed_ = 0;
  return found;
}

std::optional<SubmapRelocation> SubmapCheck::search(const Pose2& grid_pose, const Pose2& plan_pose,
                                                    const Pose2& registered) const {
  std::vector<std::size_t> scans;
  std::vector<Pose2> poses;
  for (const Joined& j : joined_) {
    scans.push_back(j.scan);
    poses.push_back(j.pose);
  }
  const ScanObservation cloud = build_submap(log_, scans, poses, grid_pose, options_.submap);
  if (cloud.size() < options_.coarse_points / 4)
    return std::nullopt;
  const ScanObservation coarse = thin(cloud, options_.coarse_points);

  // World metres from the plan filter's pose. The best placement near it is compared with
  // the best away from it that also lies near where the registration puts the robot.
  const auto shift_of = [&](const Pose2& p) {
    return (p.translation() - plan_pose.translation()).norm() * scale_;
  };
  const auto is_near = [&](const Pose2& p) { return shift_of(p) < options_.min_shift; };
  const auto is_away = [&](const Pose2& p) {
    return shift_of(p) >= options_.min_shift &&
           (p.translation() - registered.translation()).norm() * scale_ <=
               options_.max_from_registration;
  };
  // The lattice around the plan filter's pose (plan metres).
  const double step = options_.search_step / scale_;
  const auto cells = static_cast<int>(std::floor(options_.search_distance / options_.search_step));
  const auto turns = static_cast<int>(std::floor(options_.search_heading / options_.heading_step));
  std::vector<Pose2> lattice;
  for (int ix = -cells; ix <= cells; ++ix) {
    for (int iy = -cells; iy <= cells; ++iy) {
      for (int it = -turns; it <= turns; ++it) {
        lattice.push_back({plan_pose.x + ix * step, plan_pose.y + iy * step,
                           plan_pose.theta + it * options_.heading_step});
      }
    }
  }
  const std::vector<double> s = scores(field_, coarse, lattice, scale_);
  std::size_t near = lattice.size() / 2;  // the lattice's centre: the plan filter's pose
  std::vector<std::size_t> far;
  for (std::size_t k = 0; k < lattice.size(); ++k) {
    if (is_near(lattice[k])) {
      if (s[k] > s[near])
        near = k;
    } else if (is_away(lattice[k])) {
      far.push_back(k);
    }
  }
  if (far.empty())
    return std::nullopt;
  const std::size_t keep = std::min<std::size_t>(3, far.size());
  std::partial_sort(far.begin(), far.begin() + static_cast<std::ptrdiff_t>(keep), far.end(),
                    [&](std::size_t a, std::size_t b) { return s[a] > s[b]; });
  // Refined with every point, down to a sixteenth of the lattice's steps.
  const int levels = 4;
  const Placement here = refine(field_, cloud, scale_, lattice[near], step / 2.0,
                                options_.heading_step / 2.0, levels, is_near);
  Placement away;
  for (std::size_t k = 0; k < keep; ++k) {
    const Placement p = refine(field_, cloud, scale_, lattice[far[k]], step / 2.0,
                               options_.heading_step / 2.0, levels, is_away);
    if (p.score > away.score)
      away = p;
  }
  const double shift = shift_of(away.pose);
  const double before = field_.mean_beam_likelihood(cloud, here.pose, scale_);
  const double after = field_.mean_beam_likelihood(cloud, away.pose, scale_);
  if (!(after >= before + options_.min_gain))  // NaN: the plan cannot tell
    return std::nullopt;
  return SubmapRelocation{
      .plan_pose = away.pose, .shift = shift, .share_before = before, .share_after = after};
}

}  // namespace floorgrid
