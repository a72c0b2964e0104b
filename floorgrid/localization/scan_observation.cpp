#include "floorgrid/localization/scan_observation.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

ScanObservation make_observation(const LaserScan& scan, const ObservationOptions& options) {
  ScanObservation obs;
  obs.max_range = scan.max_range;
  const Pose2 laser_in_robot = scan.robot_pose.between(scan.laser_pose);
  obs.laser_origin = laser_in_robot.translation();
  std::vector<std::size_t> returns;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (scan.is_return(i)) {
      returns.push_back(i);
    } else if (scan.range_kind(i) == RangeKind::no_return) {
      ++obs.no_returns;
    }
  }
  const std::size_t keep =
      std::min(returns.size(), static_cast<std::size_t>(std::max(0, options.max_beams)));
  for (std::size_t k = 0; k < keep; ++k) {
    // Evenly spread: the k-th of `keep` equal strides through the returns.
    const std::size_t i = returns[k * returns.size() / keep];
    const double a = laser_in_robot.theta + scan.angle(i);
    const double r = scan.ranges[i];
    obs.angle.push_back(static_cast<float>(a));
    obs.range.push_back(static_cast<float>(r));
    obs.end_x.push_back(static_cast<float>(obs.laser_origin.x() + r * std::cos(a)));
    obs.end_y.push_back(static_cast<float>(obs.laser_origin.y() + r * std::sin(a)));
    obs.beam.push_back(static_cast<int>(i));
  }
  return obs;
}

}  // namespace floorgrid
