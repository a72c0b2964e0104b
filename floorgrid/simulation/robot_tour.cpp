#include "floorgrid/simulation/robot_tour.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace floorgrid {

std::vector<TimedPose> drive_tour(const std::vector<Eigen::Vector2d>& waypoints,
                                  const TourOptions& options) {
  std::vector<TimedPose> poses;
  if (waypoints.empty())
    return poses;
  Pose2 pose{waypoints[0].x(), waypoints[0].y(), 0.0};
  if (waypoints.size() > 1) {
    const Eigen::Vector2d d = waypoints[1] - waypoints[0];
    pose.theta = std::atan2(d.y(), d.x());
  }
  double time = options.start_time;
  poses.push_back({time, pose});
  const double max_turn = options.turn_rate * options.tick;
  for (std::size_t next = 1; next < waypoints.size(); ++next) {
    const Eigen::Vector2d goal = waypoints[next];
    // A safety bound: no leg takes longer than driving it twice plus two full turns.
    const double leg = (goal - pose.translation()).norm();
    const int max_ticks =
        static_cast<int>((2.0 * leg / options.speed + 4.0 * std::numbers::pi / options.turn_rate) /
                         options.tick) +
        10;
    for (int k = 0; k < max_ticks; ++k) {
      const Eigen::Vector2d to_goal = goal - pose.translation();
      const double distance = to_goal.norm();
      if (distance < options.arrive_distance)
        break;
      const double error = normalize_angle(std::atan2(to_goal.y(), to_goal.x()) - pose.theta);
      const double turn = std::clamp(error, -max_turn, max_turn);
      double step = 0.0;
      if (std::abs(error) < options.align_angle) {
        step = std::min(options.speed * options.tick, distance) * std::cos(error);
      }
      // Move along the arc's chord: turn half, step, turn half (exact for small turns).
      pose.theta = normalize_angle(pose.theta + turn / 2);
      pose.x += step * std::cos(pose.theta);
      pose.y += step * std::sin(pose.theta);
      pose.theta = normalize_angle(pose.theta + turn / 2);
      time += options.tick;
      poses.push_back({time, pose});
    }
  }
  return poses;
}

std::vector<TimedPose> drive_tour_for(const std::vector<Eigen::Vector2d>& waypoints,
                                      double duration, const TourOptions& options) {
  std::vector<TimedPose> once = drive_tour(waypoints, options);
  const double once_seconds = once.empty() ? 0.0 : once.back().time - once.front().time;
  if (!(duration > 0.0) || once_seconds <= 0.0)
    return once;
  // Forth, back, forth, ...: the robot never jumps, it turns round at either end. Each pass
  // takes about as long as the first (the turns at the ends are a few seconds more), so one
  // pass more than the duration needs is driven and the rest cut off.
  const auto passes = static_cast<std::size_t>(std::ceil(duration / once_seconds)) + 1;
  std::vector<Eigen::Vector2d> longer;
  longer.reserve(passes * waypoints.size());
  longer.push_back(waypoints.front());
  for (std::size_t pass = 0; pass < passes; ++pass) {
    if (pass % 2 == 0)
      longer.insert(longer.end(), waypoints.begin() + 1, waypoints.end());
    else
      longer.insert(longer.end(), waypoints.rbegin() + 1, waypoints.rend());
  }
  std::vector<TimedPose> poses = drive_tour(longer, options);
  // Half a tick of slack: the times are sums of ticks, not exact multiples.
  const double end = options.start_time + duration + 0.5 * options.tick;
  const auto past =
      std::find_if(poses.begin(), poses.end(), [end](const TimedPose& p) { return p.time > end; });
  poses.erase(past, poses.end());
  return poses;
}

double path_length(const std::vector<TimedPose>& poses) {
  double total = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    total += (poses[i].pose.translation() - poses[i - 1].pose.translation()).norm();
  }
  return total;
}

}  // namespace floorgrid
