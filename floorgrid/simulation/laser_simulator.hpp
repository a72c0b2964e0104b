#pragma once

#include <cstddef>
#include <map>
#include <numbers>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"

namespace floorgrid {

/// The simulated laser (SPEC "Synthetic datasets": 361 beams over 180 degrees, range noise
/// sigma 0.02 m, 1% random readings, max range 30 m).
struct LaserSpec {
  int beams = 361;                               ///< readings per scan, >= 1
  double start_angle = -std::numbers::pi / 2.0;  ///< radians, beam 0 relative to the laser pose
  double angle_increment = std::numbers::pi / 360.0;  ///< radians between neighbouring beams
  double max_range = 30.0;                            ///< metres; "no return" reads exactly this
  double range_noise_sigma = 0.02;        ///< metres, standard deviation of the range noise, >= 0
  double random_reading_fraction = 0.01;  ///< probability in [0, 1] of a random reading
  Pose2 laser_in_robot{0.15, 0.0, 0.0};   ///< the laser's mounting pose in the robot frame
};

/// Checks `spec`; throws InputError naming the field (`laser.beams`, `laser.max_range`, ...)
/// when one is out of range or not finite.
void validate_laser_spec(const LaserSpec& spec);

/// One simulated beam: what the laser reports and what the beam truly met.
struct SimulatedBeam {
  /// metres, in [0, max_range]: the reported reading. Exactly max_range for a beam that met
  /// nothing within max_range ("no return"); also max_range for a hit whose noisy range was
  /// clamped there (the beam keeps its hit fields, but a log reader sees "no return").
  double reading = 0.0;
  double true_range = 0.0;  ///< metres: exact distance to the surface met, or max_range if none
  int segment = -1;         ///< index of the segment met (SegmentRayCaster::segments), or -1
  int layer = -1;           ///< Segment::layer of the segment met (its kind tag), or -1
  bool random = false;      ///< the reading is a random one, uniform in (0, true_range)

  /// Whether the true beam met a surface within max_range (whatever the reading says).
  bool hit() const { return segment >= 0; }
};

/// One simulated scan in the world frame.
struct SimulatedScan {
  Pose2 robot_pose_in_world;     ///< the true robot pose, world metres and radians
  Pose2 laser_pose_in_world;     ///< the true laser pose: robot_pose_in_world ∘ laser_in_robot
  double start_angle = 0.0;      ///< radians, as LaserSpec
  double angle_increment = 0.0;  ///< radians, as LaserSpec
  double max_range = 0.0;        ///< metres, as LaserSpec
  std::vector<SimulatedBeam> beams;  ///< beam i at laser angle start_angle + i * angle_increment

  /// Angle of beam `i` in the world frame, radians (not wrapped).
  double world_angle(std::size_t i) const {
    return laser_pose_in_world.theta + (start_angle + static_cast<double>(i) * angle_increment);
  }
};

/// Simulates one scan from the true robot pose. Per beam, in beam order: with probability
/// random_reading_fraction the reading is uniform in (0, true_range) (marked random: something
/// unexpected stopped the beam before the surface it would have met; a beam meeting nothing
/// draws in (0, max_range)); otherwise a
/// beam that meets a surface within max_range reads its true range plus normal noise of sigma
/// range_noise_sigma, clamped to [0, max_range], and a beam that meets nothing reads exactly
/// max_range. The true range and what the beam met are recorded whatever the reading. Uses
/// `random` only (deterministic for a given state); throws InputError on a bad spec.
SimulatedScan simulate_scan(const SegmentRayCaster& caster, const Pose2& robot_pose_in_world,
                            const LaserSpec& spec, Random& random);

/// The scan as a log holds it: type FLASER, start angle, increment and max range of the scan,
/// min range 0, readings as float (a reading that rounds to max_range in float is read back as
/// "no return"), and the poses given, which in a simulated log are the NOISY odometry poses, not
/// the true ones.
LaserScan to_laser_scan(const SimulatedScan& scan, const Pose2& laser_pose_in_odom,
                        const Pose2& robot_pose_in_odom, double timestamp);

/// Counts of beams of one or more scans, by what they report and what they met.
struct LaserScanCounts {
  std::size_t beams = 0;          ///< readings
  std::size_t returns = 0;        ///< readings in (0, max_range): what a log reader takes for a hit
  std::size_t no_returns = 0;     ///< readings equal to max_range
  std::size_t zero_readings = 0;  ///< readings of exactly 0 (a very near hit clamped there)
  std::size_t random = 0;         ///< random readings (also counted above by their value)
  std::size_t true_hits = 0;      ///< beams that truly met a surface within max_range
  /// Beams that truly met a surface within max_range, per Segment::layer of the surface (whatever
  /// the reading: a random reading does not hide what the beam would have met).
  std::map<int, std::size_t> true_hits_per_layer;

  /// The fraction of beams that truly met a surface of `layer`; 0 when there are no beams.
  double layer_fraction(int layer) const;
  /// Adds another count.
  LaserScanCounts& operator+=(const LaserScanCounts& other);
};

/// Counts the beams of `scan`.
LaserScanCounts count_beams(const SimulatedScan& scan);

}  // namespace floorgrid
