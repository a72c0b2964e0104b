#include "floorgrid/simulation/laser_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

Segment segment(double ax, double ay, double bx, double by, int layer = 0) {
  Segment s;
  s.a = {ax, ay};
  s.b = {bx, by};
  s.layer = layer;
  return s;
}

/// A closed box room [-hx, hx] x [-hy, hy] on one layer.
std::vector<Segment> box_room(double hx, double hy, int layer = 0) {
  return {segment(hx, -hy, hx, hy, layer), segment(hx, hy, -hx, hy, layer),
          segment(-hx, hy, -hx, -hy, layer), segment(-hx, -hy, hx, -hy, layer)};
}

/// Distance from `p` (inside the box) to the box wall along `angle`.
double range_in_box(const Eigen::Vector2d& p, double angle, double hx, double hy) {
  const double c = std::cos(angle), s = std::sin(angle);
  const double tx = c > 0 ? (hx - p.x()) / c : (c < 0 ? (-hx - p.x()) / c : 1e300);
  const double ty = s > 0 ? (hy - p.y()) / s : (s < 0 ? (-hy - p.y()) / s : 1e300);
  return std::min(tx, ty);
}

LaserSpec noiseless() {
  LaserSpec spec;
  spec.range_noise_sigma = 0.0;
  spec.random_reading_fraction = 0.0;
  return spec;
}

TEST(LaserSimulator, NoiselessScanOfABoxRoomIsAnalytic) {
  const SegmentRayCaster caster(box_room(3, 2));
  const Pose2 robot{0.5, -0.3, 0.4};
  Random random(1);
  const SimulatedScan scan = simulate_scan(caster, robot, noiseless(), random);
  ASSERT_EQ(scan.beams.size(), 361u);
  // The laser sits 0.15 m ahead of the robot centre.
  EXPECT_NEAR(scan.laser_pose_in_world.x, 0.5 + 0.15 * std::cos(0.4), 1e-15);
  EXPECT_NEAR(scan.laser_pose_in_world.y, -0.3 + 0.15 * std::sin(0.4), 1e-15);
  EXPECT_NEAR(scan.world_angle(0), 0.4 - std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(scan.world_angle(360), 0.4 + std::numbers::pi / 2, 1e-12);
  for (std::size_t i = 0; i < scan.beams.size(); ++i) {
    const SimulatedBeam& b = scan.beams[i];
    const double expected =
        range_in_box(scan.laser_pose_in_world.translation(), scan.world_angle(i), 3, 2);
    ASSERT_TRUE(b.hit()) << i;
    EXPECT_NEAR(b.true_range, expected, 1e-12) << i;
    EXPECT_EQ(b.reading, b.true_range) << i;  // no noise, no random readings
    EXPECT_EQ(b.layer, 0);
    EXPECT_FALSE(b.random);
  }
}

TEST(LaserSimulator, NoiseHasTheSpecifiedStatistics) {
  const SegmentRayCaster caster(box_room(10, 10));
  const LaserSpec spec;  // the SPEC's laser: sigma 0.02 m, 1% random readings, 30 m
  Random random(2024);
  double sum = 0.0, sum_sq = 0.0, random_sum = 0.0;
  std::size_t noisy = 0, random_readings = 0, beams = 0;
  for (int k = 0; k < 200; ++k) {
    const Pose2 robot{random.uniform(-8, 8), random.uniform(-8, 8), random.uniform(-3, 3)};
    const SimulatedScan scan = simulate_scan(caster, robot, spec, random);
    for (const SimulatedBeam& b : scan.beams) {
      ++beams;
      ASSERT_TRUE(b.hit());  // a closed room: every beam meets a wall within 30 m
      ASSERT_GE(b.reading, 0.0);
      ASSERT_LE(b.reading, spec.max_range);
      if (b.random) {
        ++random_readings;
        random_sum += b.reading / b.true_range;  // uniform in (0, 1) of the true range
        ASSERT_GT(b.reading, 0.0);
        ASSERT_LT(b.reading, b.true_range);  // never past the surface the beam meets
        continue;
      }
      const double error = b.reading - b.true_range;
      sum += error;
      sum_sq += error * error;
      ++noisy;
    }
  }
  const double n = static_cast<double>(noisy);
  const double mean = sum / n;
  const double std_dev = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_LT(std::abs(mean), 4 * 0.02 / std::sqrt(n));  // four standard errors
  EXPECT_NEAR(std_dev, 0.02, 0.05 * 0.02);
  const double fraction = static_cast<double>(random_readings) / static_cast<double>(beams);
  EXPECT_NEAR(fraction, 0.01, 4 * std::sqrt(0.01 * 0.99 / static_cast<double>(beams)));
  // Random readings are uniform over (0, true range): as a fraction of it, mean 1/2 and
  // standard error 1 / sqrt(12 n).
  const double nr = static_cast<double>(random_readings);
  EXPECT_NEAR(random_sum / nr, 0.5, 4 * 1.0 / std::sqrt(12.0 * nr));
}

TEST(LaserSimulator, NoReturnReadsExactlyMaxRange) {
  // One wall ahead of the robot at 5 m and one behind beyond max range: a laser looking
  // backwards sees nothing.
  const SegmentRayCaster caster({segment(5, -50, 5, 50, 0), segment(-40, -50, -40, 50, 0)});
  LaserSpec spec;  // with noise and random readings
  spec.laser_in_robot = {0, 0, std::numbers::pi};
  Random random(9);
  std::size_t no_returns = 0;
  for (int k = 0; k < 50; ++k) {
    const SimulatedScan scan = simulate_scan(caster, {0, 0, 0}, spec, random);
    for (const SimulatedBeam& b : scan.beams) {
      EXPECT_FALSE(b.hit());
      EXPECT_EQ(b.true_range, spec.max_range);
      EXPECT_EQ(b.layer, -1);
      EXPECT_EQ(b.segment, -1);
      if (!b.random) {
        EXPECT_EQ(b.reading, spec.max_range);  // exactly, no noise on a no-return
        ++no_returns;
      }
    }
    const LaserScanCounts counts = count_beams(scan);
    EXPECT_EQ(counts.true_hits, 0u);
    EXPECT_EQ(counts.no_returns + counts.returns + counts.zero_readings, counts.beams);
    EXPECT_EQ(counts.no_returns, scan.beams.size() - counts.random);
  }
  EXPECT_GT(no_returns, 50u * 361u * 95u / 100u);
}

TEST(LaserSimulator, NoisyReadingsAreClampedToTheRange) {
  LaserSpec spec;
  spec.random_reading_fraction = 0.0;
  spec.laser_in_robot = {};
  Random random(4);
  // A wall 5 mm short of max range: about 40% of the noisy readings reach max range.
  const SegmentRayCaster far({segment(29.995, -1, 29.995, 1, 1)});
  spec.beams = 1;
  spec.start_angle = 0.0;
  std::size_t at_max = 0;
  for (int k = 0; k < 2000; ++k) {
    const SimulatedScan scan = simulate_scan(far, {0, 0, 0}, spec, random);
    const SimulatedBeam& b = scan.beams[0];
    ASSERT_TRUE(b.hit());
    EXPECT_EQ(b.layer, 1);
    ASSERT_LE(b.reading, spec.max_range);
    if (b.reading == spec.max_range) {
      ++at_max;
      EXPECT_EQ(count_beams(scan).no_returns, 1u);  // reads as "no return", still a true hit
      EXPECT_EQ(count_beams(scan).true_hits, 1u);
    }
  }
  EXPECT_NEAR(static_cast<double>(at_max) / 2000, 0.4013, 0.05);  // P(noise > 0.005 / 0.02 sigma)
  // A wall 5 mm ahead: about 40% of the readings clamp to exactly 0.
  const SegmentRayCaster near({segment(0.005, -1, 0.005, 1, 0)});
  std::size_t at_zero = 0;
  for (int k = 0; k < 2000; ++k) {
    const SimulatedScan scan = simulate_scan(near, {0, 0, 0}, spec, random);
    ASSERT_GE(scan.beams[0].reading, 0.0);
    if (scan.beams[0].reading == 0.0) {
      ++at_zero;
      EXPECT_EQ(count_beams(scan).zero_readings, 1u);
    }
  }
  EXPECT_NEAR(static_cast<double>(at_zero) / 2000, 0.4013, 0.05);
}

TEST(LaserSimulator, CountsTrueHitsPerLayerTag) {
  // Laser at the origin facing +y, beams from +x (beam 0) to -x (beam 360). The right wall and
  // the top wall right of x = 1 are furniture (layer 2), the rest walls (layer 0): beam i (angle
  // i / 2 degrees) meets furniture while tan(angle) < 4, i.e. for i = 0..151.
  const std::vector<Segment> scene = {segment(4, -4, 4, 4, 2), segment(4, 4, 1, 4, 2),
                                      segment(1, 4, -4, 4, 0), segment(-4, 4, -4, -4, 0)};
  const SegmentRayCaster caster(scene);
  LaserSpec spec;
  spec.laser_in_robot = {};
  Random random(6);
  const SimulatedScan scan = simulate_scan(caster, {0, 0, std::numbers::pi / 2}, spec, random);
  const LaserScanCounts counts = count_beams(scan);
  EXPECT_EQ(counts.beams, 361u);
  EXPECT_EQ(counts.true_hits, 361u);
  EXPECT_EQ(counts.true_hits_per_layer.at(2), 152u);
  EXPECT_EQ(counts.true_hits_per_layer.at(0), 209u);
  EXPECT_EQ(counts.true_hits_per_layer.size(), 2u);
  EXPECT_DOUBLE_EQ(counts.layer_fraction(2), 152.0 / 361.0);
  EXPECT_EQ(counts.layer_fraction(7), 0.0);
  for (std::size_t i = 0; i < scan.beams.size(); ++i)
    EXPECT_EQ(scan.beams[i].layer, i <= 151 ? 2 : 0) << i;
  LaserScanCounts total = counts;
  total += counts;
  EXPECT_EQ(total.beams, 722u);
  EXPECT_EQ(total.true_hits_per_layer.at(2), 304u);
  EXPECT_EQ(total.random, 2 * counts.random);
  EXPECT_EQ(LaserScanCounts{}.layer_fraction(2), 0.0);
}

TEST(LaserSimulator, ToLaserScanCarriesTheReadingsAndTheGivenPoses) {
  const SegmentRayCaster caster({segment(5, -50, 5, 50, 0)});
  LaserSpec spec;
  spec.random_reading_fraction = 0.0;
  Random random(12);
  const SimulatedScan scan = simulate_scan(caster, {0, 0, 0}, spec, random);
  const Pose2 odom_robot{1.0, 2.0, 0.1};
  const Pose2 odom_laser = odom_robot.compose(spec.laser_in_robot);
  const LaserScan log = to_laser_scan(scan, odom_laser, odom_robot, 1234.5);
  EXPECT_EQ(log.type, "FLASER");
  EXPECT_EQ(log.start_angle, spec.start_angle);
  EXPECT_EQ(log.angle_increment, spec.angle_increment);
  EXPECT_EQ(log.max_range, spec.max_range);
  EXPECT_EQ(log.min_range, 0.0);
  EXPECT_EQ(log.timestamp, 1234.5);
  EXPECT_EQ(log.laser_pose.x, odom_laser.x);
  EXPECT_EQ(log.laser_pose.theta, odom_laser.theta);
  EXPECT_EQ(log.robot_pose.y, odom_robot.y);
  ASSERT_EQ(log.ranges.size(), scan.beams.size());
  std::size_t no_return = 0;
  for (std::size_t i = 0; i < log.ranges.size(); ++i) {
    EXPECT_EQ(log.ranges[i], static_cast<float>(scan.beams[i].reading));
    const bool below_max = scan.beams[i].reading < spec.max_range;
    EXPECT_EQ(log.range_kind(i), below_max ? RangeKind::hit : RangeKind::no_return) << i;
    no_return += below_max ? 0 : 1;
    if (!scan.beams[i].hit()) {
      EXPECT_EQ(log.range_kind(i), RangeKind::no_return) << i;
    }
  }
  // The wall, 4.85 m ahead of the laser, is within 30 m for |angle| < acos(4.85 / 30) = 80.7
  // degrees: the outer 2 x 18 beams see nothing.
  EXPECT_GE(no_return, 36u);
  EXPECT_LE(no_return, 40u);
}

TEST(LaserSimulator, SameSeedSameScanOtherSeedOther) {
  const SegmentRayCaster caster(box_room(6, 4));
  const LaserSpec spec;
  Random a(77), b(77), c(78);
  const SimulatedScan x = simulate_scan(caster, {1, 1, 0.2}, spec, a);
  const SimulatedScan y = simulate_scan(caster, {1, 1, 0.2}, spec, b);
  const SimulatedScan z = simulate_scan(caster, {1, 1, 0.2}, spec, c);
  int differ = 0;
  for (std::size_t i = 0; i < x.beams.size(); ++i) {
    EXPECT_EQ(x.beams[i].reading, y.beams[i].reading);
    EXPECT_EQ(x.beams[i].random, y.beams[i].random);
    differ += x.beams[i].reading != z.beams[i].reading ? 1 : 0;
  }
  EXPECT_GT(differ, 300);
}

TEST(LaserSimulator, BadSpecNamesTheField) {
  const SegmentRayCaster caster(box_room(1, 1));
  Random random(1);
  const auto with = [&](auto edit, const char* field) {
    LaserSpec spec;
    edit(spec);
    test::expect_input_error([&] { simulate_scan(caster, {}, spec, random); }, {field});
  };
  with([](LaserSpec& s) { s.beams = 0; }, "laser.beams");
  with([](LaserSpec& s) { s.max_range = 0.0; }, "laser.max_range");
  with([](LaserSpec& s) { s.range_noise_sigma = -0.1; }, "laser.range_noise_sigma");
  with([](LaserSpec& s) { s.random_reading_fraction = 1.5; }, "laser.random_reading_fraction");
  with([](LaserSpec& s) { s.angle_increment = std::nan(""); }, "laser.angle_increment");
}

}  // namespace
}  // namespace floorgrid
