#include "floorgrid/simulation/simulated_run.hpp"

#include <algorithm>
#include <cmath>

#include "floorgrid/robot/motion_model.hpp"

namespace floorgrid {

LaserSpec preset_laser(const SimulationPreset& p) {
  LaserSpec spec;
  spec.beams = p.beams;
  spec.start_angle = -p.field_of_view / 2;
  spec.angle_increment = p.field_of_view / (p.beams - 1);
  spec.max_range = p.max_range;
  spec.range_noise_sigma = p.range_noise_sigma;
  spec.random_reading_fraction = p.random_reading_fraction;
  spec.laser_in_robot = {p.laser_forward_offset, 0.0, 0.0};
  return spec;
}

SimulatedRun simulate_run(const std::vector<TimedPose>& trajectory, const SegmentRayCaster& caster,
                          const SimulationPreset& p, Random& odometry_random,
                          Random& laser_random) {
  const LaserSpec spec = preset_laser(p);
  const int scan_every = std::max(1, static_cast<int>(std::lround(p.scan_period / p.tour.tick)));
  SimulatedRun run;
  Pose2 odometry;  // the odometry frame starts at the robot's start
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const TimedPose& now = trajectory[i];
    double tv = 0.0, rv = 0.0;
    if (i > 0) {
      const OdometryMotion truth = odometry_motion(trajectory[i - 1].pose, now.pose);
      const OdometryMotion noisy = sample_noisy_motion(truth, p.odometry, odometry_random);
      const Pose2 before = odometry;
      odometry = apply_motion(odometry, noisy);
      tv = noisy.trans / p.tour.tick;
      rv = normalize_angle(odometry.theta - before.theta) / p.tour.tick;
    }
    run.log.odometry.push_back({odometry, tv, rv, 0.0, now.time, 0});
    if (i % static_cast<std::size_t>(scan_every) != 0)
      continue;
    const SimulatedScan scan = simulate_scan(caster, now.pose, spec, laser_random);
    run.log.scans.push_back(
        to_laser_scan(scan, odometry.compose(spec.laser_in_robot), odometry, now.time));
    run.slam_inputs.push_back(to_slam_map_input(scan));
    run.counts += count_beams(scan);
  }
  run.final_odometry = odometry;
  return run;
}

}  // namespace floorgrid
