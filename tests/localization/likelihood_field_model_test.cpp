#include "floorgrid/localization/likelihood_field_model.hpp"

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
/// 20 and 139 up: centre lines x = 1.025, 8.975, y = 1.025, 6.975) and a solid 0.5 m pillar
/// (cells 120..129 x 50..59); free inside, unknown outside, as in a SLAM map.
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

/// The scan a robot at `pose_in_map` takes in a world `scale` times the map (about the map's
/// origin), with endpoints exactly on the walls' centre lines: 60 beams over 180 degrees.
ScanObservation room_scan(const Pose2& pose_in_map, double scale = 1.0, int beams = 60) {
  const Rect room{1.025 * scale, 1.025 * scale, 8.975 * scale, 6.975 * scale};
  const Rect pillar{6.025 * scale, 2.525 * scale, 6.475 * scale, 2.975 * scale};
  const Pose2 pose{pose_in_map.x * scale, pose_in_map.y * scale, pose_in_map.theta};
  const Eigen::Vector2d laser = pose.transform(kLaserOrigin);
  ScanObservation scan;
  scan.laser_origin = kLaserOrigin;
  scan.max_range = 30.0;
  for (int k = 0; k < beams; ++k) {
    const double a = -kPi / 2 + kPi * k / (beams - 1);
    const Eigen::Vector2d d(std::cos(pose.theta + a), std::sin(pose.theta + a));
    const double r = std::min(exit_range(room, laser, d), entry_range(pillar, laser, d));
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

TEST(LikelihoodField, LogLikelihoodIsTheSumOfHandComputedBeamTerms) {
  // One vertical wall: cells ix = 50 (x in [2.50, 2.55), centre line 2.525); free to its left,
  // unknown to its right.
  GridGeometry geometry;
  geometry.width = 100;
  geometry.height = 100;
  geometry.resolution = kResolution;
  OccupancyGrid grid(geometry, CellState::free);
  for (int iy = 0; iy < 100; ++iy) {
    grid.set_state(50, iy, CellState::occupied);
    for (int ix = 51; ix < 100; ++ix)
      grid.set_state(ix, iy, CellState::unknown);
  }
  LikelihoodFieldOptions options;
  options.beam_weight = 0.5;
  const LikelihoodFieldModel model(grid, options);

  // A particle at (1.0, 2.0) facing +y: robot-frame (a, b) lies at map (1 - b, 2 + a).
  const ParticleSet particle = particles_at({{1.0, 2.0, kPi / 2}});
  const auto add_to = [](ScanObservation& to, double map_x, double map_y) {
    to.angle.push_back(0.0f);
    to.range.push_back(1.0f);
    to.end_x.push_back(static_cast<float>(map_y - 2.0));
    to.end_y.push_back(static_cast<float>(1.0 - map_x));
  };
  ScanObservation scan;
  const auto add_endpoint = [&](double map_x, double map_y) { add_to(scan, map_x, map_y); };
  const double z_hit = 0.9, z_rand = 0.1, sigma = 0.1;
  const auto log_p = [&](double d) {
    return std::log(z_hit * std::exp(-d * d / (2 * sigma * sigma)) + z_rand);
  };
  add_endpoint(2.525, 2.0125);  // on a wall cell's centre: log(z_hit + z_rand) = 0
  add_endpoint(2.425, 2.9125);  // two cells (0.1 m) off: the Gaussian at sigma
  add_endpoint(2.225, 1.0125);  // six cells (0.3 m) off
  add_endpoint(0.025, 3.0125);  // 2.5 m off: beyond max_distance (2 m), the floor
  add_endpoint(-1.0, 2.0);      // off the map: the floor
  add_endpoint(2.725, 4.0125);  // unknown cell 0.2 m right of the wall: scored as free
  std::vector<double> out;
  model.log_likelihood(scan, particle, out, 1);
  ASSERT_EQ(out.size(), 1u);
  const double by_hand = std::log(z_hit + z_rand) + log_p(0.1) + log_p(0.3) + std::log(z_rand) +
                         std::log(z_rand) + log_p(0.2);
  EXPECT_NEAR(out[0], 0.5 * by_hand, 1e-5);
  EXPECT_NEAR(log_p(0.1), std::log(0.9 * std::exp(-0.5) + 0.1), 1e-15);

  // The per-point queries agree.
  EXPECT_NEAR(model.point_log_likelihood({2.425, 2.9}), log_p(0.1), 1e-6);
  EXPECT_NEAR(model.distance_to_occupied({2.425, 2.9}), 0.1, 1e-6);
  EXPECT_NEAR(model.distance_to_occupied({0.025, 2.9}), 2.0, 1e-6);
  EXPECT_NEAR(model.point_log_likelihood({50.0, 2.9}), std::log(z_rand), 1e-6);

  // With unknown cells not free, the endpoint in unknown space gets the floor.
  options.unknown_is_free = false;
  const LikelihoodFieldModel strict(grid, options);
  strict.log_likelihood(scan, particle, out, 1);
  EXPECT_NEAR(out[0], 0.5 * (by_hand - log_p(0.2) + std::log(z_rand)), 1e-5);

  // The mean beam likelihood: the Gaussian parts alone, averaged over the known endpoints
  // (the one off the map says nothing; the unknown cell 0.2 m from the wall is known).
  const auto g = [&](double d) { return std::exp(-d * d / (2 * sigma * sigma)); };
  EXPECT_NEAR(model.mean_beam_likelihood(scan, particle.pose(0)),
              (1.0 + g(0.1) + g(0.3) + 0.0 + g(0.2)) / 5.0, 1e-6);

  // Endpoints deep in unknown space (more than known_margin from every observed cell) are not
  // known either; with fewer than min_known_share known, the map cannot tell: NaN.
  ScanObservation far;
  const auto add_far = [&](double map_x, double map_y) { add_to(far, map_x, map_y); };
  add_far(2.525, 2.0125);  // on the wall: known
  for (int i = 0; i < 4; ++i)
    add_far(3.3 + 0.2 * i, 2.0);  // 0.75 m or more beyond the wall: unknown
  EXPECT_TRUE(std::isnan(model.mean_beam_likelihood(far, particle.pose(0))));  // 1 of 5 known
  add_far(2.525, 2.5125);
  EXPECT_NEAR(model.mean_beam_likelihood(far, particle.pose(0)), 1.0, 1e-6);  // 2 of 6
}

TEST(LikelihoodField, TruePoseScoresHigherThanShiftedOrTurnedPoses) {
  const LikelihoodFieldModel model(room_grid());
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth);
    std::vector<double> out;
    model.log_likelihood(scan, particles_at(pose_and_neighbours(truth)), out);
    EXPECT_NEAR(out[0], 0.0, 0.2) << "nearly every endpoint lies on a wall cell";
    for (std::size_t j = 1; j < out.size(); ++j)
      EXPECT_GT(out[0], out[j] + 1.0) << "truth " << truth.x << ", " << truth.y << " vs " << j;
  }
}

TEST(LikelihoodField, MeanBeamLikelihoodIsNearOneAtTheTruePoseOnly) {
  const LikelihoodFieldModel model(room_grid());
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth);
    const std::vector<Pose2> poses = pose_and_neighbours(truth);
    const double at_truth = model.mean_beam_likelihood(scan, truth);
    EXPECT_GE(at_truth, 0.97);
    EXPECT_LE(at_truth, 1.0);
    // A shift along one wall leaves the endpoints on that wall explained, so single neighbours
    // can keep up to ~85%; on average they lose far more.
    double sum = 0.0;
    for (std::size_t j = 1; j < poses.size(); ++j) {
      const double off = model.mean_beam_likelihood(scan, poses[j]);
      EXPECT_GE(off, 0.0);
      EXPECT_LT(off, 0.9) << "pose " << j;
      sum += off;
    }
    EXPECT_LT(sum / static_cast<double>(poses.size() - 1), 0.65);
  }
}

TEST(LikelihoodField, ScanOfALargerWorldIsExplainedBestAtItsScale) {
  const LikelihoodFieldModel model(room_grid());
  const std::vector<double> scales = {0.9, 1.0, 1.05, 1.08, 1.1, 1.12, 1.15, 1.2, 1.3};
  for (const Pose2& truth : kTruePoses) {
    const ScanObservation scan = room_scan(truth, 1.1);
    std::vector<double> out;
    model.log_likelihood(scan, particles_at(std::vector<Pose2>(scales.size(), truth), scales), out);
    const auto best = std::max_element(out.begin(), out.end()) - out.begin();
    EXPECT_DOUBLE_EQ(scales[best], 1.1);
    EXPECT_GE(model.mean_beam_likelihood(scan, truth, 1.1), 0.97);
    EXPECT_LT(model.mean_beam_likelihood(scan, truth, 1.0), 0.8);
  }
}

TEST(LikelihoodField, YawedGridGivesTheResultOfTheUnyawedMap) {
  const Pose2 origin{3.0, -2.0, 0.7};
  const LikelihoodFieldModel flat(room_grid());
  const LikelihoodFieldModel yawed(room_grid(origin));
  Random random(3);
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
  const ScanObservation scan = room_scan(kTruePoses[0]);
  std::vector<double> a, b;
  flat.log_likelihood(scan, in_flat, a);
  yawed.log_likelihood(scan, in_yawed, b);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], b[i], 1e-3) << i;
    const double f = flat.mean_beam_likelihood(scan, in_flat.pose(i));
    const double y = yawed.mean_beam_likelihood(scan, in_yawed.pose(i));
    EXPECT_EQ(std::isnan(f), std::isnan(y)) << i;
    if (!std::isnan(f)) {
      EXPECT_NEAR(f, y, 1e-3) << i;
    }
  }
  EXPECT_NEAR(yawed.distance_to_occupied(origin.transform({1.025, 4.0})), 0.0, 1e-9);
  EXPECT_NEAR(yawed.distance_to_occupied(origin.transform({1.325, 4.0})), 0.3, 1e-6);
}

TEST(LikelihoodField, ThreadCountDoesNotChangeTheResult) {
  const LikelihoodFieldModel model(room_grid());
  Random random(4);
  ParticleSet particles;
  for (int i = 0; i < 5000; ++i) {
    // Some particles off the map, all with a scale.
    particles.x.push_back(random.uniform(-2.0, 12.0));
    particles.y.push_back(random.uniform(-2.0, 10.0));
    particles.theta.push_back(random.uniform(-kPi, kPi));
    particles.scale.push_back(random.uniform(0.9, 1.1));
  }
  const ScanObservation scan = room_scan(kTruePoses[1], 1.0, 61);  // not a multiple of 8
  std::vector<double> one, other;
  model.log_likelihood(scan, particles, one, 1);
  for (const int threads : {2, 3, 7, 0}) {
    model.log_likelihood(scan, particles, other, threads);
    EXPECT_EQ(one, other) << threads << " threads";
  }
  // Each particle's value is the one it gets alone.
  for (const std::size_t i : {0u, 1234u, 4999u}) {
    ParticleSet single = particles_at({particles.pose(i)}, {particles.scale[i]});
    model.log_likelihood(scan, single, other, 1);
    EXPECT_EQ(other[0], one[i]);
  }
}

TEST(LikelihoodField, EmptyInputs) {
  const LikelihoodFieldModel model(room_grid());
  std::vector<double> out{1.0, 2.0};
  model.log_likelihood(ScanObservation{}, particles_at({{3, 3, 0}, {4, 4, 0}}), out);
  EXPECT_EQ(out, std::vector<double>({0.0, 0.0}));
  model.log_likelihood(room_scan(kTruePoses[0]), ParticleSet{}, out);
  EXPECT_TRUE(out.empty());
  EXPECT_TRUE(std::isnan(model.mean_beam_likelihood(ScanObservation{}, {3, 3, 0})));
}

TEST(LikelihoodField, RejectsBadOptionsNamingTheField) {
  const OccupancyGrid grid = room_grid();
  const auto field_of = [&](const LikelihoodFieldOptions& options) -> std::string {
    try {
      LikelihoodFieldModel model(grid, options);
    } catch (const InputError& e) {
      return e.field();
    }
    return "";
  };
  EXPECT_EQ(field_of({.sigma_hit = 0.0}), "likelihood_field.sigma_hit");
  EXPECT_EQ(field_of({.z_hit = -1.0}), "likelihood_field.z_hit");
  EXPECT_EQ(field_of({.z_rand = 0.0}), "likelihood_field.z_rand");
  EXPECT_EQ(field_of({.max_distance = std::nan("")}), "likelihood_field.max_distance");
  EXPECT_EQ(field_of({.beam_weight = 0.0}), "likelihood_field.beam_weight");
  EXPECT_EQ(field_of({.known_margin = -1.0}), "likelihood_field.known_margin");
  EXPECT_EQ(field_of({.min_known_share = 1.5}), "likelihood_field.min_known_share");
  EXPECT_EQ(field_of({}), "");
  EXPECT_THROW(LikelihoodFieldModel(OccupancyGrid{}), InputError);
}

}  // namespace
}  // namespace floorgrid
