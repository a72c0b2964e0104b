#include "floorgrid/localization/beam_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kResolution = 0.05;

/// A 10 x 8 m grid holding a room whose walls are one cell thick (cells 20 and 179 across,
/// 20 and 139 up) and a solid 0.5 m pillar (cells 120..129 x 50..59); free inside, unknown
/// outside, as in a SLAM map. The faces a ray meets from inside: x = 1.05 and 8.95, y = 1.05
/// and 6.95; the pillar [6.0, 6.5] x [2.5, 3.0].
OccupancyGrid room_grid(const Pose2& origin = {}) {
  GridGeometry geometry;
  geometry.width = 200;
  geometry.height = 160;
  geometry.resolution = kResolution;
  geometry.origin = origin;
  OccupancyGrid grid(geometry, CellState::unknown);
  for (int iy = 20; iy <= 139; ++iy) {
    for (int ix = 20; ix <= 179; ++ix) {
      const bool wall = ix == 20 || ix == 179 || iy == 20 || iy == 139;
      const bool pillar = ix >= 120 && ix <= 129 && iy >= 50 && iy <= 59;
      grid.set_state(ix, iy, wall || pillar ? CellState::occupied : CellState::free);
    }
  }
  return grid;
}

/// An axis-aligned rectangle, metres.
struct Rect {
  double x0, y0, x1, y1;
};

/// Distance from `o` along unit `d` to where the ray leaves `r` (o inside r).
double exit_range(const Rect& r, const Eigen::Vector2d& o, const Eigen::Vector2d& d) {
  double t = std::numeric_limits<double>::infinity();
  if (d.x() > 0)
    t = std::min(t, (r.x1 - o.x()) / d.x());
  if (d.x() < 0)
    t = std::min(t, (r.x0 - o.x()) / d.x());
  if (d.y() > 0)
    t = std::min(t, (r.y1 - o.y()) / d.y());
  if (d.y() < 0)
    t = std::min(t, (r.y0 - o.y()) / d.y());
  return t;
}

/// Distance from `o` along unit `d` to where the ray enters `r` (o outside r), or +inf.
double entry_range(const Rect& r, const Eigen::Vector2d& o, const Eigen::Vector2d& d) {
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  const double lo[2] = {r.x0, r.y0}, hi[2] = {r.x1, r.y1};
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (o[axis] < lo[axis] || o[axis] > hi[axis])
        return std::numeric_limits<double>::infinity();
      continue;
    }
    double ta = (lo[axis] - o[axis]) / d[axis], tb = (hi[axis] - o[axis]) / d[axis];
    if (ta > tb)
      std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

const Eigen::Vector2d kLaserOrigin(0.15, 0.0);

/// Analytic range from `laser` (world) along world angle `angle` in the room scaled by `scale`.
double room_range(const Eigen::Vector2d& laser, double angle, double scale) {
  const Rect room{1.05 * scale, 1.05 * scale, 8.95 * scale, 6.95 * scale};
  const Rect pillar{6.0 * scale, 2.5 * scale, 6.5 * scale, 3.0 * scale};
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  return std::min(exit_range(room, laser, d), entry_range(pillar, laser, d));
}

/// The scan a robot at `pose_in_map` takes in a world `scale` times the map (about the map's
/// origin), ranges exactly to the faces: `beams` beams over 180 degrees.
ScanObservation room_scan(const Pose2& pose_in_map, double scale = 1.0, int beams = 60) {
  const Pose2 pose{pose_in_map.x * scale, pose_in_map.y * scale, pose_in_map.theta};
  const Eigen::Vector2d laser = pose.transform(kLaserOrigin);
  ScanObservation scan;
  scan.laser_origin = kLaserOrigin;
  scan.max_range = 30.0;
  for (int k = 0; k < beams; ++k) {
    const double a = -kPi / 2 + kPi * k / (beams - 1);
    const double r = room_range(laser, pose.theta + a, scale);
    scan.angle.push_back(static_cast<float>(a));
    scan.range.push_back(static_cast<float>(r));
    scan.end_x.push_back(static_cast<float>(kLaserOrigin.x() + r * std::cos(a)));
    scan.end_y.push_back(static_cast<float>(kLaserOrigin.y() + r * std::sin(a)));
    scan.beam.push_back(k);
  }
  return scan;
}

/// Particles at the given poses (and scales, when given).
ParticleSet particles_at(const std::vector<Pose2>& poses, const std::vector<double>& scales = {}) {
  ParticleSet p;
  for (const Pose2& pose : poses) {
    p.x.push_back(pose.x);
    p.y.push_back(pose.y);
    p.theta.push_back(pose.theta);
  }
  p.scale = scales;
  return p;
}

const std::vector<Pose2> kTruePoses = {
    {3.0, 3.3, 0.3}, {5.0, 5.5, 2.0}, {7.5, 2.0, -2.5}, {2.0, 6.0, -1.0}, {4.2, 1.8, 1.2}};

/// The pose and its neighbours 0.2 m off along x and y and 5 degrees off in heading.
std::vector<Pose2> pose_and_neighbours(const Pose2& p) {
  const double turn = 5.0 * kPi / 180.0;
  return {p,
          {p.x + 0.2, p.y, p.theta},
          {p.x - 0.2, p.y, p.theta},
          {p.x, p.y + 0.2, p.theta},
          {p.x, p.y - 0.2, p.theta},
          {p.x + 0.14, p.y + 0.14, p.theta},
          {p.x, p.y, p.theta + turn},
          {p.x, p.y, p.theta - turn}};
}

TEST(BeamModel, ExpectedRangesInASquareRoomAreAnalytic) {
  const BeamModel model(room_grid());
  const BeamModel yawed(room_grid({-4.0, 7.0, 2.5}));
  const Pose2 origin{-4.0, 7.0, 2.5};
  for (const Pose2& pose : kTruePoses) {
    for (const double scale : {1.0, 1.1, 0.93}) {
      const ScanObservation scan = room_scan(pose, scale, 181);
      const std::vector<double> ranges = model.expected_ranges(scan, pose, scale);
      const std::vector<double> in_yawed = yawed.expected_ranges(scan, origin.compose(pose), scale);
      // In world metres: the laser sits at (scale * pose) ∘ laser_origin in the scaled room.
      const Pose2 world{pose.x * scale, pose.y * scale, pose.theta};
      const Eigen::Vector2d laser = world.transform(kLaserOrigin);
      ASSERT_EQ(ranges.size(), scan.size());
      for (std::size_t k = 0; k < scan.size(); ++k) {
        const double truth = room_range(laser, pose.theta + scan.angle[k], scale);
        EXPECT_NEAR(ranges[k], truth, 1e-6) << "beam " << k;
        EXPECT_NEAR(in_yawed[k], truth, 1e-6) << "beam " << k;
      }
    }
  }
  // A beam that meets nothing within the max range expects the max range.
  ScanObservation short_scan = room_scan(kTruePoses[0]);
  short_scan.max_range = 0.5;
  for (const double r : model.expected_ranges(short_scan, kTruePoses[0]))
    EXPECT_EQ(r, 0.5);
}

TEST(BeamModel, MixtureIntegratesToOneOverTheRange) {
  const OccupancyGrid grid = room_grid();
  const double z_max = 10.0;
  for (const BeamModelOptions& options :
       {BeamModelOptions{},
        BeamModelOptions{.weight_hit = 0.6,
        .weight_unexpected = 0.2,
        .weight_random = 0.1,
        .weight_max = 0.1,
        .sigma_hit = 0.3,
        .lambda_unexpected = 2.0},
        BeamModelOptions{
            .weight_hit = 5, .weight_unexpected = 1, .weight_random = 1, .weight_max = 3}}) {
    const BeamModel model(grid, options);
    const double unexpected_share =
        options.weight_unexpected / (options.weight_hit + options.weight_unexpected +
                                     options.weight_random + options.weight_max);
    for (const double z_exp : {0.0, 0.02, 0.3, 4.0, 9.9, 9.99, 10.0}) {
      // Midpoint rule on a fine lattice; the discontinuities cost O(step).
      const int steps = 1'000'000;
      const double h = z_max / steps;
      double integral = 0.0;
      for (int i = 0; i < steps; ++i)
        integral += model.beam_probability((i + 0.5) * h, z_exp, z_max) * h;
      // With z_exp = 0 (the laser inside a wall) the unexpected part has no support.
      EXPECT_NEAR(integral, z_exp > 0.0 ? 1.0 : 1.0 - unexpected_share, 3e-4) << "z_exp " << z_exp;
    }
    EXPECT_EQ(model.beam_probability(-0.1, 3.0, z_max), 0.0);
    EXPECT_EQ(model.beam_probability(10.1, 3.0, z_max), 0.0);
  }
}

TEST(BeamModel, LogLikelihoodIsTheSumOfHandComputedBeamTerms) {
  BeamModelOptions options;
  options.beam_weight = 0.7;
  options.weight_max = 0.05;
  const BeamModel model(room_grid(), options);
  // Particle at (3, 3.3) facing +x; laser at (3.15, 3.3). Beams along +x (wall at 8.95),
  // +y (6.95), -x (1.05) and -y (1.05): expected 5.8, 3.65, 2.1 and 2.25.
  const Pose2 pose{3.0, 3.3, 0.0};
  ScanObservation scan;
  scan.laser_origin = kLaserOrigin;
  scan.max_range = 8.0;
  const double angles[] = {0.0, kPi / 2, kPi, -kPi / 2};
  const double measured[] = {5.83, 2.0, 2.1, 7.95};  // hit, short, exact, near max
  for (int k = 0; k < 4; ++k) {
    scan.angle.push_back(static_cast<float>(angles[k]));
    scan.range.push_back(static_cast<float>(measured[k]));
    scan.end_x.push_back(0.0f);  // the beam model does not read endpoints
    scan.end_y.push_back(0.0f);
  }
  const double z_exp[] = {5.8, 3.65, 2.1, 2.25};
  // eq. 3.43-3.47 with the weights normalized (sum 1.05).
  const double total = 0.8 + 0.1 + 0.1 + 0.05;
  const double sigma = 0.1, lambda = 0.5, z_max = 8.0;
  const auto phi = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  double by_hand = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double z = static_cast<float>(measured[k]), e = z_exp[k];
    const double eta = 1.0 / (phi((z_max - e) / sigma) - phi(-e / sigma));
    const double hit = eta * std::exp(-0.5 * (z - e) * (z - e) / (sigma * sigma)) /
                       std::sqrt(2 * kPi * sigma * sigma);
    const double unexpected =
        z < e ? lambda * std::exp(-lambda * z) / (1 - std::exp(-lambda * e)) : 0.0;
    const double random = 1.0 / z_max;
    const double max = std::abs(z - z_max) < 0.1 ? 1.0 / 0.1 : 0.0;
    by_hand += std::log((0.8 * hit + 0.1 * unexpected + 0.1 * random + 0.05 * max) / total);
  }
  const std::vector<double> expected = model.expected_ranges(scan, pose);
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(expected[k], z_exp[k], 1e-9);
  std::vector<double> out;
  model.log_likelihood(scan, particles_at({pose}), out, 1);
  EXPECT_NEAR(out[0], 0.7 * by_hand, 1e-9);
  // Mean beam likelihood: the unnormalized hit part.
  double mean = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double e = static_cast<float>(measured[k]) - z_exp[k];
    mean += std::exp(-0.5 * e * e / (sigma * sigma)) / 4;
  }
  EXPECT_NEAR(model.mean_beam_likelihood(scan, pose), mean, 1e-9);
}

TEST(BeamModel, TruePoseScoresHigherThanShiftedOrTurnedPoses) {
  const BeamModel model(room_grid());
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth);
    std::vector<double> out;
    model.log_likelihood(scan, particles_at(pose_and_neighbours(truth)), out);
    for (std::size_t j = 1; j < out.size(); ++j)
      EXPECT_GT(out[0], out[j] + 1.0) << "truth " << truth.x << ", " << truth.y << " vs " << j;
  }
}

TEST(BeamModel, MeanBeamLikelihoodIsNearOneAtTheTruePoseOnly) {
  const BeamModel model(room_grid());
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth);
    const std::vector<Pose2> poses = pose_and_neighbours(truth);
    EXPECT_GE(model.mean_beam_likelihood(scan, truth), 0.999);
    // A shift along one wall leaves the beams across it explained, so single neighbours can
    // keep up to ~80%; on average they lose far more.
    double sum = 0.0;
    for (std::size_t j = 1; j < poses.size(); ++j) {
      const double off = model.mean_beam_likelihood(scan, poses[j]);
      EXPECT_LT(off, 0.9) << "pose " << j;
      sum += off;
    }
    EXPECT_LT(sum / static_cast<double>(poses.size() - 1), 0.65);
  }
}

TEST(BeamModel, ScanOfALargerWorldIsExplainedBestAtItsScale) {
  const BeamModel model(room_grid());
  const std::vector<double> scales = {0.9, 1.0, 1.05, 1.08, 1.1, 1.12, 1.15, 1.2, 1.3};
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth, 1.1);
    std::vector<double> out;
    model.log_likelihood(scan, particles_at(std::vector<Pose2>(scales.size(), truth), scales), out);
    const auto best = std::max_element(out.begin(), out.end()) - out.begin();
    EXPECT_DOUBLE_EQ(scales[best], 1.1);
    EXPECT_GE(model.mean_beam_likelihood(scan, truth, 1.1), 0.999);
  }
}

TEST(BeamModel, YawedGridGivesTheResultOfTheUnyawedMap) {
  const Pose2 origin{3.0, -2.0, 0.7};
  const BeamModel flat(room_grid());
  const BeamModel yawed(room_grid(origin));
  Random random(5);
  ParticleSet in_flat, in_yawed;
  for (int i = 0; i < 200; ++i) {
    const Pose2 p{random.uniform(1.5, 8.5), random.uniform(1.5, 6.5), random.uniform(-kPi, kPi)};
    const Pose2 q = origin.compose(p);
    in_flat.x.push_back(p.x);
    in_flat.y.push_back(p.y);
    in_flat.theta.push_back(p.theta);
    in_yawed.x.push_back(q.x);
    in_yawed.y.push_back(q.y);
    in_yawed.theta.push_back(q.theta);
  }
  const ScanObservation scan = room_scan(kTruePoses[2]);
  std::vector<double> a, b;
  flat.log_likelihood(scan, in_flat, a);
  yawed.log_likelihood(scan, in_yawed, b);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], b[i], 1e-6 * std::max(1.0, std::abs(a[i]))) << i;
}

TEST(BeamModel, ThreadCountDoesNotChangeTheResult) {
  const BeamModel model(room_grid());
  Random random(6);
  ParticleSet particles;
  for (int i = 0; i < 2000; ++i) {
    particles.x.push_back(random.uniform(-2.0, 12.0));
    particles.y.push_back(random.uniform(-2.0, 10.0));
    particles.theta.push_back(random.uniform(-kPi, kPi));
    particles.scale.push_back(random.uniform(0.9, 1.1));
  }
  const ScanObservation scan = room_scan(kTruePoses[3], 1.0, 37);
  std::vector<double> one, other;
  model.log_likelihood(scan, particles, one, 1);
  for (const int threads : {2, 3, 8}) {
    model.log_likelihood(scan, particles, other, threads);
    EXPECT_EQ(one, other) << threads << " threads";
  }
  for (const double v : one)
    EXPECT_TRUE(std::isfinite(v));
}

TEST(BeamModel, RejectsBadOptionsAndAMissingMaxRange) {
  const OccupancyGrid grid = room_grid();
  const auto field_of = [&](const BeamModelOptions& options) -> std::string {
    try {
      BeamModel model(grid, options);
    } catch (const InputError& e) {
      return e.field();
    }
    return "";
  };
  EXPECT_EQ(field_of({.weight_hit = -1}), "beam_model.weight_hit");
  EXPECT_EQ(field_of({.weight_random = 0}), "beam_model.weight_random");
  EXPECT_EQ(field_of({.sigma_hit = 0}), "beam_model.sigma_hit");
  EXPECT_EQ(field_of({.lambda_unexpected = -2}), "beam_model.lambda_unexpected");
  EXPECT_EQ(field_of({.max_range = -1}), "beam_model.max_range");
  EXPECT_EQ(field_of({.max_window = 0}), "beam_model.max_window");
  EXPECT_EQ(field_of({.beam_weight = std::nan("")}), "beam_model.beam_weight");
  EXPECT_EQ(field_of({}), "");
  EXPECT_THROW(BeamModel(OccupancyGrid{}), InputError);

  const BeamModel model(grid);
  ScanObservation scan = room_scan(kTruePoses[0]);
  scan.max_range = 0.0;
  std::vector<double> out;
  EXPECT_THROW(model.log_likelihood(scan, particles_at({kTruePoses[0]}), out), InputError);
  // The option's max range stands in for the scan's.
  const BeamModel with_range(grid, {.max_range = 30.0});
  with_range.log_likelihood(scan, particles_at({kTruePoses[0]}), out);
  EXPECT_TRUE(std::isfinite(out[0]));
}

}  // namespace
}  // namespace floorgrid
