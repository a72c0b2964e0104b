#include "floorgrid/simulation/laser_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

// Uniform in the open interval (0, limit): Random::uniform includes its lower end.
double draw_random_reading(double limit, Random& random) {
  double reading = 0.0;
  do {
    reading = random.uniform(0.0, limit);
  } while (!(reading > 0.0));
  return reading;
}

}  // namespace

void validate_laser_spec(const LaserSpec& spec) {
  if (spec.beams < 1)
    throw InputError("must be >= 1 (got " + std::to_string(spec.beams) + ")", {}, 0, "laser.beams");
  if (!std::isfinite(spec.start_angle))
    throw InputError("must be a finite number " + got(spec.start_angle), {}, 0,
                     "laser.start_angle");
  if (!std::isfinite(spec.angle_increment))
    throw InputError("must be a finite number " + got(spec.angle_increment), {}, 0,
                     "laser.angle_increment");
  if (!(std::isfinite(spec.max_range) && spec.max_range > 0.0))
    throw InputError("must be a finite number > 0 " + got(spec.max_range), {}, 0,
                     "laser.max_range");
  if (!(std::isfinite(spec.range_noise_sigma) && spec.range_noise_sigma >= 0.0))
    throw InputError("must be a finite number >= 0 " + got(spec.range_noise_sigma), {}, 0,
                     "laser.range_noise_sigma");
  if (!(spec.random_reading_fraction >= 0.0 && spec.random_reading_fraction <= 1.0))
    throw InputError("must be in [0, 1] " + got(spec.random_reading_fraction), {}, 0,
                     "laser.random_reading_fraction");
  const Pose2& m = spec.laser_in_robot;
  if (!(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.theta)))
    throw InputError("must be finite", {}, 0, "laser.laser_in_robot");
}

SimulatedScan simulate_scan(const SegmentRayCaster& caster, const Pose2& robot_pose_in_world,
                            const LaserSpec& spec, Random& random) {
  validate_laser_spec(spec);
  SimulatedScan scan;
  scan.robot_pose_in_world = robot_pose_in_world;
  scan.laser_pose_in_world = robot_pose_in_world.compose(spec.laser_in_robot);
  scan.start_angle = spec.start_angle;
  scan.angle_increment = spec.angle_increment;
  scan.max_range = spec.max_range;
  scan.beams.resize(static_cast<std::size_t>(spec.beams));
  const Eigen::Vector2d origin = scan.laser_pose_in_world.translation();
  for (std::size_t i = 0; i < scan.beams.size(); ++i) {
    SimulatedBeam& beam = scan.beams[i];
    const std::optional<RayHit> hit = caster.cast(origin, scan.world_angle(i), spec.max_range);
    beam.true_range = hit ? hit->range : spec.max_range;
    if (hit) {
      beam.segment = static_cast<int>(hit->segment);
      beam.layer = hit->layer;
    }
    // The draws per beam are fixed (one Bernoulli, then one uniform or one normal when there is
    // a hit), so a scene change alters only the beams it touches.
    if (random.bernoulli(spec.random_reading_fraction)) {
      beam.random = true;
      // Something unexpected stops the beam before the surface it would have met: a laser
      // cannot read beyond a wall, so a random reading never reaches past the true range.
      beam.reading = draw_random_reading(beam.true_range, random);
    } else if (hit) {
      const double noisy = hit->range + random.normal(spec.range_noise_sigma);
      beam.reading = std::clamp(noisy, 0.0, spec.max_range);
    } else {
      beam.reading = spec.max_range;
    }
  }
  return scan;
}

LaserScan to_laser_scan(const SimulatedScan& scan, const Pose2& laser_pose_in_odom,
                        const Pose2& robot_pose_in_odom, double timestamp) {
  LaserScan out;
  out.type = "FLASER";
  out.start_angle = scan.start_angle;
  out.angle_increment = scan.angle_increment;
  out.max_range = scan.max_range;
  out.min_range = 0.0;
  out.ranges.reserve(scan.beams.size());
  for (const SimulatedBeam& beam : scan.beams)
    out.ranges.push_back(static_cast<float>(beam.reading));
  out.laser_pose = laser_pose_in_odom;
  out.robot_pose = robot_pose_in_odom;
  out.timestamp = timestamp;
  return out;
}

double LaserScanCounts::layer_fraction(int layer) const {
  if (beams == 0)
    return 0.0;
  const auto it = true_hits_per_layer.find(layer);
  const std::size_t n = it == true_hits_per_layer.end() ? 0 : it->second;
  return static_cast<double>(n) / static_cast<double>(beams);
}

LaserScanCounts& LaserScanCounts::operator+=(const LaserScanCounts& other) {
  beams += other.beams;
  returns += other.returns;
  no_returns += other.no_returns;
  zero_readings += other.zero_readings;
  random += other.random;
  true_hits += other.true_hits;
  for (const auto& [layer, n] : other.true_hits_per_layer)
    true_hits_per_layer[layer] += n;
  return *this;
}

LaserScanCounts count_beams(const SimulatedScan& scan) {
  LaserScanCounts counts;
  for (const SimulatedBeam& beam : scan.beams) {
    ++counts.beams;
    if (beam.reading >= scan.max_range)
      ++counts.no_returns;
    else if (beam.reading > 0.0)
      ++counts.returns;
    else
      ++counts.zero_readings;
    if (beam.random)
      ++counts.random;
    if (beam.hit()) {
      ++counts.true_hits;
      ++counts.true_hits_per_layer[beam.layer];
    }
  }
  return counts;
}

}  // namespace floorgrid
