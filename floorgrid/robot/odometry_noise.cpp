#include "floorgrid/robot/odometry_noise.hpp"

#include "floorgrid/core/random.hpp"

namespace floorgrid {

RobotLog add_odometry_noise(const RobotLog& log, const MotionNoise& noise, std::uint64_t seed) {
  RobotLog out = log;
  Random random(seed);
  if (out.scans.empty())
    return out;
  Pose2 noisy = log.scans.front().robot_pose;
  for (std::size_t i = 0; i < out.scans.size(); ++i) {
    if (i > 0) {
      const OdometryMotion truth =
          odometry_motion(log.scans[i - 1].robot_pose, log.scans[i].robot_pose);
      noisy = apply_motion(noisy, sample_noisy_motion(truth, noise, random));
    }
    const Pose2 laser_in_robot = log.scans[i].robot_pose.between(log.scans[i].laser_pose);
    out.scans[i].robot_pose = noisy;
    out.scans[i].laser_pose = noisy.compose(laser_in_robot);
  }
  return out;
}

}  // namespace floorgrid
