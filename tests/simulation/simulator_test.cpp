// The simulator's truth itself: the gridmap, the log and the plan agree with the exact warp.
#include "floorgrid/simulation/simulator.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "floorgrid/core/error.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"

namespace floorgrid {
namespace {

/// Each preset simulated once per test run (a second or so each). "office@600" is the office
/// driven for 600 seconds (SimulationOptions::duration).
const SimulatedDataset& dataset(const std::string& key, std::uint64_t seed = 1) {
  static std::map<std::pair<std::string, std::uint64_t>, std::unique_ptr<SimulatedDataset>> cache;
  auto& slot = cache[{key, seed}];
  if (!slot) {
    const std::size_t at = key.find('@');
    SimulationOptions options;
    if (at != std::string::npos)
      options.duration = std::stod(key.substr(at + 1));
    slot = std::make_unique<SimulatedDataset>(simulate(key.substr(0, at), seed, options));
  }
  return *slot;
}

bool occupied_within(const OccupancyGrid& grid, const Eigen::Vector2d& point, int reach) {
  const Eigen::Vector2d c = grid.geometry().to_cell_coordinates(point);
  const int ix = static_cast<int>(std::floor(c.x())), iy = static_cast<int>(std::floor(c.y()));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (grid.is_occupied(ix + dx, iy + dy))
        return true;
    }
  }
  return false;
}

/// The true laser pose of every scan (the log's scans are every k-th odometry tick).
std::vector<Pose2> true_laser_poses(const SimulatedDataset& d) {
  std::map<double, Pose2> by_time;
  for (const TimedPose& p : d.true_trajectory)
    by_time[p.time] = p.pose;
  std::vector<Pose2> poses;
  for (const LaserScan& scan : d.log.scans) {
    const Pose2 robot = by_time.at(scan.timestamp);
    poses.push_back(robot.compose({d.preset.laser_forward_offset, 0.0, 0.0}));
  }
  return poses;
}

class SimulatorPresets : public ::testing::TestWithParam<std::string> {};

TEST_P(SimulatorPresets, ObservedPlanWallsLandOnOccupiedCells) {
  const SimulatedDataset& d = dataset(GetParam());
  const PlanTruth truth = d.truth();
  // Which wall points did the laser truly see? Cast every scan's beams from the true poses.
  const auto world = d.building.world_segments();
  const SegmentRayCaster caster(world);
  const auto poses = true_laser_poses(d);
  std::vector<Eigen::Vector2d> seen;  // wall points hit, world metres
  for (std::size_t i = 0; i < poses.size(); i += 3) {
    for (std::size_t k = 0; k < d.log.scans[i].ranges.size(); k += 2) {
      const double angle = poses[i].theta + d.log.scans[i].angle(k);
      const auto hit = caster.cast(poses[i].translation(), angle, d.preset.max_range);
      if (hit && hit->layer == static_cast<int>(SurfaceKind::wall)) {
        seen.push_back(poses[i].translation() +
                       hit->range * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
      }
    }
  }
  ASSERT_GT(seen.size(), 10000u);
  // Each seen wall point, taken into the plan and through the exact truth, lies within one cell
  // of an occupied gridmap cell.
  std::size_t on_wall = 0;
  for (const auto& p : seen) {
    on_wall += occupied_within(d.gridmap, truth.plan_to_grid(p * d.plan_scale), 1) ? 1 : 0;
  }
  EXPECT_GT(static_cast<double>(on_wall) / seen.size(), 0.99) << GetParam();
}

TEST_P(SimulatorPresets, TruthInverseUndoesTheForwardMap) {
  const SimulatedDataset& d = dataset(GetParam());
  const PlanTruth truth = d.truth();
  Random random(3);
  const Eigen::AlignedBox2d box = d.plan.bounds();
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(random.uniform(box.min().x(), box.max().x()),
                            random.uniform(box.min().y(), box.max().y()));
    const InverseResult back = truth.grid_to_plan(truth.plan_to_grid(p));
    ASSERT_TRUE(back.converged);
    worst = std::max(worst, (back.point - p).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST_P(SimulatorPresets, LoggedRangesMatchTheTrueScansUpToTheNoiseModel) {
  const SimulatedDataset& d = dataset(GetParam());
  const SegmentRayCaster caster(d.building.world_segments());
  const auto poses = true_laser_poses(d);
  double sum = 0.0, sum_sq = 0.0;
  std::size_t n = 0, beams = 0, outliers = 0;
  for (std::size_t i = 0; i < poses.size(); i += 5) {
    const LaserScan& scan = d.log.scans[i];
    for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
      const double angle = poses[i].theta + scan.angle(k);
      const auto hit = caster.cast(poses[i].translation(), angle, scan.max_range);
      const double truth = hit ? hit->range : scan.max_range;
      const double error = scan.ranges[k] - truth;
      ++beams;
      if (!hit) {
        // Nothing within range reads "no return", or a random reading below max range.
        EXPECT_LE(scan.ranges[k], scan.max_range);
        continue;
      }
      if (std::abs(error) > 5 * d.preset.range_noise_sigma) {
        ++outliers;  // random readings (1%) and clamped readings
        EXPECT_LT(scan.ranges[k], truth + 5 * d.preset.range_noise_sigma);  // never past a wall
        continue;
      }
      sum += error;
      sum_sq += error * error;
      ++n;
    }
  }
  const double mean = sum / n, sigma = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_LT(std::abs(mean), 0.002);
  EXPECT_NEAR(sigma, d.preset.range_noise_sigma, 0.1 * d.preset.range_noise_sigma);
  EXPECT_NEAR(static_cast<double>(outliers) / beams, d.preset.random_reading_fraction, 0.004);
}

TEST_P(SimulatorPresets, LogPosesAreNoisyOdometryNotTheTruth) {
  const SimulatedDataset& d = dataset(GetParam());
  const Pose2 start = d.true_trajectory.front().pose;
  std::map<double, Pose2> truth;
  for (const TimedPose& p : d.true_trajectory)
    truth[p.time] = start.between(p.pose);
  double largest = 0.0;
  for (const LaserScan& scan : d.log.scans) {
    const Pose2& t = truth.at(scan.timestamp);
    largest = std::max(largest, (scan.robot_pose.translation() - t.translation()).norm());
  }
  // The odometry starts exact at the robot's start and drifts by metres over the run.
  EXPECT_EQ(d.log.scans.front().robot_pose.x, 0.0);
  EXPECT_GT(largest, 0.5);
  EXPECT_GT(d.statistics.final_odometry_error, 0.1);
}

TEST_P(SimulatorPresets, PresetPromisesHold) {
  const SimulatedDataset& d = dataset(GetParam());
  const SimulationStatistics& s = d.statistics;
  EXPECT_GE(s.furniture_fraction, 0.20);
  EXPECT_LT(s.rooms_visited, s.rooms);  // a region never visited
  EXPECT_LE(s.max_bend_strain, d.preset.max_bend_strain + 1e-12);
  EXPECT_NEAR(s.bend_deviation, d.preset.bend_deviation, 1e-6);
  EXPECT_GE(std::abs(s.room_rotation_deg), 1.0);
  EXPECT_LE(std::abs(s.room_rotation_deg), 3.0);
  EXPECT_GT(s.min_room_jacobian, 0.0);  // the rotated room does not fold
  EXPECT_GE(d.manual_pairs.size(), 30);
  EXPECT_LE(d.manual_pairs.size(), 60);
  EXPECT_LE(std::abs(d.plan_scale - 1.0), d.preset.max_plan_scale_error + 1e-12);
  // The unvisited room's interior is mostly unknown in the gridmap.
  const PlanTruth truth = d.truth();
  for (const Room& room : d.building.rooms) {
    if (room.visited)
      continue;
    std::size_t unknown = 0, total = 0;
    for (double x = room.interior.min().x() + 0.5; x < room.interior.max().x() - 0.5; x += 0.25) {
      for (double y = room.interior.min().y() + 0.5; y < room.interior.max().y() - 0.5; y += 0.25) {
        int ix = 0, iy = 0;
        ++total;
        if (!d.gridmap.geometry().cell_of(truth.warp().world_to_grid({x, y}), ix, iy) ||
            d.gridmap.state(ix, iy) == CellState::unknown) {
          ++unknown;
        }
      }
    }
    EXPECT_GT(static_cast<double>(unknown) / total, 0.9) << room.name;  // its door is shut
  }
}

TEST_P(SimulatorPresets, ManualPairsFollowTheTruthWithAboutAPixelOfNoise) {
  const SimulatedDataset& d = dataset(GetParam());
  const PlanTruth truth = d.truth();
  double sum_sq = 0.0;
  for (Eigen::Index i = 0; i < d.manual_pairs.size(); ++i) {
    sum_sq += (truth.plan_to_grid(d.manual_pairs.points_in_plan.col(i)) -
               d.manual_pairs.points_in_grid.col(i))
                  .squaredNorm();
  }
  const double rms = std::sqrt(sum_sq / d.manual_pairs.size());
  EXPECT_GT(rms, 0.02);
  EXPECT_LT(rms, 0.09);
}

// The last: a run of a given length (the tour driven over and over) keeps every promise too.
INSTANTIATE_TEST_SUITE_P(Presets, SimulatorPresets,
                         ::testing::Values("office", "warehouse", "bent-office", "office-inches",
                                           "office@1200"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name)
                             c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

TEST(SimulatorDuration, RunLastsThatLongAtFifteenScansASecond) {
  const SimulatedDataset& once = dataset("office");
  const SimulatedDataset& d = dataset("office@1200");
  const double duration = 1200, period = 1.0 / 15.0;
  ASSERT_GT(duration, 2.0 * once.statistics.duration);  // the tour is driven more than twice
  const std::vector<LaserScan>& scans = d.log.scans;
  EXPECT_NEAR(static_cast<double>(scans.size()), duration * 15.0 + 1.0, 1.0);
  EXPECT_EQ(d.log.odometry.size(), scans.size());  // an odometry reading with every scan
  EXPECT_EQ(d.statistics.scans, scans.size());
  EXPECT_NEAR(scans.back().timestamp - scans.front().timestamp, duration, period);
  EXPECT_NEAR(d.statistics.duration, duration, period);
  for (std::size_t i = 1; i < scans.size(); ++i)
    ASSERT_NEAR(scans[i].timestamp - scans[i - 1].timestamp, period, 1e-6) << i;
  EXPECT_DOUBLE_EQ(d.preset.scan_period, period);
  // The same building and world, driven for longer: more than twice the path.
  EXPECT_EQ(d.building.outline.sizes(), once.building.outline.sizes());
  EXPECT_EQ(d.plan_scale, once.plan_scale);
  EXPECT_GT(d.statistics.path_length, 2.0 * once.statistics.path_length);
  EXPECT_EQ(d.true_trajectory.front().pose.x, once.true_trajectory.front().pose.x);
}

TEST(SimulatorDuration, BadDurationsAreRefusedNamingTheField) {
  for (const double bad :
       {0.0, -60.0, std::nan(""), std::numeric_limits<double>::infinity(), 1e6, 0.1}) {
    SimulationOptions options;
    options.duration = bad;
    try {
      simulate("office", 1, options);
      FAIL() << "no error for " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "duration") << bad;
      EXPECT_NE(e.message().find("must be"), std::string::npos) << e.what();
    }
  }
  SimulationOptions fine;
  fine.duration = 14400.0;
  EXPECT_NO_THROW(validate(fine));
}

TEST(Simulator, DifferentSeedsGiveDifferentBuildings) {
  const SimulatedDataset& a = dataset("office", 1);
  const SimulatedDataset& b = dataset("office", 2);
  EXPECT_NE(a.building.outline.sizes().x(), b.building.outline.sizes().x());
  EXPECT_NE(a.log.scans.size(), b.log.scans.size());
}

TEST(Simulator, UnknownPresetIsRefused) {
  try {
    simulate("castle", 1);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("castle"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("office-inches"), std::string::npos);
  }
}

}  // namespace
}  // namespace floorgrid
