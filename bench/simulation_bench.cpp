// Simulator sensing: ray casting over the world's segments, scan simulation and the SLAM-like
// gridmap. Run: build-*/bench/simulation_bench (items_per_second = rays/s or beams/s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/building.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"
#include "floorgrid/simulation/robot_tour.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
#include "floorgrid/simulation/slam_map.hpp"

namespace {

using floorgrid::Pose2;
using floorgrid::Segment;
constexpr double kPi = std::numbers::pi;

/// A world to scan: its segments and the robot poses along its tour.
struct Scene {
  std::vector<Segment> segments;
  std::vector<Pose2> poses;
  double max_range = 30.0;
};

void add_box(std::vector<Segment>& out, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
             int layer) {
  const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int i = 0; i < 4; ++i) {
    Segment s;
    s.a = c[i];
    s.b = c[(i + 1) % 4];
    s.layer = layer;
    out.push_back(s);
  }
}

/// The generated building of `kind` (seed 1), with its tour subsampled to `scans` poses.
/// A warehouse gets its racks' uprights (10 cm posts every 0.3 m along both long faces), which
/// brings it to about 11,000 segments, as in a detailed rack hall.
Scene building_scene(const char* kind, std::size_t scans) {
  floorgrid::Random random(1);
  const floorgrid::Building b = floorgrid::generate_building({kind}, random);
  Scene scene;
  scene.segments = b.world_segments();
  if (std::string(kind) == "warehouse") {
    scene.max_range = 50.0;
    for (const Eigen::AlignedBox2d& rack : b.rack_boxes) {
      const bool along_x = rack.sizes().x() >= rack.sizes().y();
      const int axis = along_x ? 0 : 1;
      for (double s = rack.min()[axis]; s + 0.1 <= rack.max()[axis]; s += 0.3) {
        for (const double across : {rack.min()[1 - axis] - 0.1, rack.max()[1 - axis]}) {
          Eigen::Vector2d lo, hi;
          lo[axis] = s;
          hi[axis] = s + 0.1;
          lo[1 - axis] = across;
          hi[1 - axis] = across + 0.1;
          add_box(scene.segments, lo, hi, 1);
        }
      }
    }
  }
  const std::vector<floorgrid::TimedPose> path = floorgrid::drive_tour(b.tour);
  const std::size_t stride = std::max<std::size_t>(1, path.size() / scans);
  for (std::size_t i = 0; i < path.size() && scene.poses.size() < scans; i += stride)
    scene.poses.push_back(path[i].pose);
  return scene;
}

const Scene& office() {
  static const Scene scene = building_scene("office", 2000);
  return scene;
}

const Scene& warehouse() {
  static const Scene scene = building_scene("warehouse", 2000);
  return scene;
}

/// 12,500 small boxes (50,000 segments) over 150 x 80 m, and random poses among them.
const Scene& clutter() {
  static const Scene scene = [] {
    Scene s;
    floorgrid::Random random(21);
    for (int i = 0; i < 12'500; ++i) {
      const Eigen::Vector2d lo(random.uniform(0, 150), random.uniform(0, 80));
      add_box(s.segments, lo,
              lo + Eigen::Vector2d(random.uniform(0.05, 0.6), random.uniform(0.05, 0.6)), 2);
    }
    for (int i = 0; i < 2000; ++i)
      s.poses.push_back({random.uniform(0, 150), random.uniform(0, 80), random.uniform(-3, 3)});
    return s;
  }();
  return scene;
}

/// 361 beams over 180 degrees from every pose of the scene, per iteration.
void cast_scans(benchmark::State& state, const Scene& scene, double cell_size) {
  const floorgrid::SegmentRayCaster caster(scene.segments, {.cell_size = cell_size});
  std::size_t rays = 0, hits = 0;
  for (auto _ : state) {
    for (const Pose2& pose : scene.poses) {
      const Eigen::Vector2d origin = pose.translation();
      for (int i = 0; i < 361; ++i) {
        const auto hit =
            caster.cast(origin, pose.theta - kPi / 2 + i * (kPi / 360), scene.max_range);
        hits += hit ? 1 : 0;
        benchmark::DoNotOptimize(hit);
      }
      rays += 361;
    }
  }
  state.counters["segments"] = static_cast<double>(scene.segments.size());
  state.counters["registrations"] = static_cast<double>(caster.registrations());
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(rays);
  state.SetItemsProcessed(static_cast<int64_t>(rays));
}

void BM_CastOffice(benchmark::State& state) {
  cast_scans(state, office(), static_cast<double>(state.range(0)) / 100.0);
}
BENCHMARK(BM_CastOffice)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_CastWarehouse(benchmark::State& state) {
  cast_scans(state, warehouse(), static_cast<double>(state.range(0)) / 100.0);
}
BENCHMARK(BM_CastWarehouse)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_CastClutter50k(benchmark::State& state) {
  cast_scans(state, clutter(), static_cast<double>(state.range(0)) / 100.0);
}
BENCHMARK(BM_CastClutter50k)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);

void BM_BuildRayCasterWarehouse(benchmark::State& state) {
  for (auto _ : state) {
    const floorgrid::SegmentRayCaster caster(warehouse().segments);
    benchmark::DoNotOptimize(caster.registrations());
  }
}
BENCHMARK(BM_BuildRayCasterWarehouse)->Unit(benchmark::kMillisecond);

/// 2,000 simulated scans of the scene with the SPEC's laser.
std::vector<floorgrid::SlamMapInput> simulated_inputs(const Scene& scene) {
  const floorgrid::SegmentRayCaster caster(scene.segments);
  floorgrid::LaserSpec spec;
  spec.max_range = scene.max_range;
  floorgrid::Random random(7);
  std::vector<floorgrid::SlamMapInput> inputs;
  for (const Pose2& pose : scene.poses)
    inputs.push_back(
        floorgrid::to_slam_map_input(floorgrid::simulate_scan(caster, pose, spec, random)));
  return inputs;
}

void BM_SimulateScansOffice(benchmark::State& state) {
  const floorgrid::SegmentRayCaster caster(office().segments);
  const floorgrid::LaserSpec spec;
  floorgrid::Random random(7);
  std::size_t beams = 0;
  floorgrid::LaserScanCounts counts;
  for (auto _ : state) {
    for (const Pose2& pose : office().poses) {
      const floorgrid::SimulatedScan scan = floorgrid::simulate_scan(caster, pose, spec, random);
      counts += floorgrid::count_beams(scan);
      beams += scan.beams.size();
    }
  }
  state.counters["scans"] = static_cast<double>(office().poses.size());
  state.counters["furniture_fraction"] = counts.layer_fraction(2);
  state.SetItemsProcessed(static_cast<int64_t>(beams));
}
BENCHMARK(BM_SimulateScansOffice)->Unit(benchmark::kMillisecond);

/// A near-isometric warp like the simulator's: a bend of the long axis (heading turning
/// linearly with x, about 0.2 m off at 40 m) then a rigid transform.
Eigen::Vector2d bend_then_rigid(const Eigen::Vector2d& p) {
  const double k = 2.5e-4;  // 1/m: curvature of the bent x axis
  const double phi = k * p.x();
  const double r = 1.0 / k - p.y();
  const Eigen::Vector2d bent(r * std::sin(phi), 1.0 / k - r * std::cos(phi));
  const double c = std::cos(0.3), s = std::sin(0.3);
  return {c * bent.x() - s * bent.y() + 5.0, s * bent.x() + c * bent.y() - 3.0};
}

void build_map(benchmark::State& state, const Scene& scene) {
  const std::vector<floorgrid::SlamMapInput> inputs = simulated_inputs(scene);
  floorgrid::CellCounts cells;
  for (auto _ : state) {
    const floorgrid::OccupancyGrid map = floorgrid::build_slam_map(inputs, bend_then_rigid);
    cells = map.counts();
  }
  state.counters["scans"] = static_cast<double>(inputs.size());
  state.counters["occupied"] = static_cast<double>(cells.occupied);
  state.counters["free"] = static_cast<double>(cells.free);
  state.counters["cells"] = static_cast<double>(cells.free + cells.occupied + cells.unknown);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(inputs.size()) * 361);
}

void BM_BuildSlamMapOffice(benchmark::State& state) {
  build_map(state, office());
}
BENCHMARK(BM_BuildSlamMapOffice)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_BuildSlamMapWarehouse(benchmark::State& state) {
  build_map(state, warehouse());
}
BENCHMARK(BM_BuildSlamMapWarehouse)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
