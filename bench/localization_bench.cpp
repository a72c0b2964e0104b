// Observation models: particle-beam evaluations per second of the likelihood field, ray casts
// per second of GridRayCaster (and of a plain cell walk, for comparison), particle evaluations
// per second of the beam model. Maps: the simulated office's and warehouse's SLAM-like gridmaps
// (seed 1; the warehouse's 2117 x 1954 cells show the effect of a field larger than the caches)
// and, when present, the fr079 SLAM map (../shared/data/fr079/slam_map.png at 0.05 m/px).
// Run: build-*/bench/localization_bench (items_per_second: see each benchmark's comment).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "floorgrid/localization/ray_marching.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace {

using floorgrid::CellState;
using floorgrid::OccupancyGrid;
using floorgrid::Pose2;
using floorgrid::ScanObservation;
constexpr double kPi = std::numbers::pi;
constexpr double kMaxRange = 30.0;  // metres, the simulated laser's

/// A map to benchmark on: the grid, scans to score and places to put particles and rays.
struct BenchMap {
  std::string name;
  OccupancyGrid grid;
  std::vector<ScanObservation> scans;        // 60 beams each
  std::vector<Eigen::Vector2d> free_points;  // centres of the free cells
};

std::vector<Eigen::Vector2d> free_cell_centres(const OccupancyGrid& grid) {
  std::vector<Eigen::Vector2d> points;
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      if (grid.state(ix, iy) == CellState::free)
        points.push_back(grid.geometry().cell_center(ix, iy));
    }
  }
  return points;
}

/// A simulated building (`preset`, seed 1): its gridmap and 32 scans of its log spread over the
/// run.
std::unique_ptr<BenchMap> make_simulated(const std::string& preset) {
  const floorgrid::SimulatedDataset data = floorgrid::simulate(preset, 1);
  auto map = std::make_unique<BenchMap>();
  map->name = preset;
  map->grid = data.gridmap;
  map->free_points = free_cell_centres(map->grid);
  const std::size_t n = data.log.scans.size();
  for (std::size_t i = 0; i < 32; ++i)
    map->scans.push_back(floorgrid::make_observation(data.log.scans[i * n / 32]));
  return map;
}

/// fr079's SLAM map with 32 scans ray cast in it from random free cells (361 beams over 180
/// degrees, 60 returns kept), or null when the map is absent.
std::unique_ptr<BenchMap> make_fr079() {
  const std::filesystem::path path =
      std::filesystem::path(FLOORGRID_DATA_DIR) / "fr079" / "slam_map.png";
  if (!std::filesystem::exists(path))
    return nullptr;
  floorgrid::io::MapMetadata settings;
  settings.resolution = 0.05;
  auto map = std::make_unique<BenchMap>();
  map->name = "fr079";
  map->grid = floorgrid::io::read_map_image(path, settings).grid;
  map->free_points = free_cell_centres(map->grid);
  const floorgrid::GridRayCaster caster(map->grid);
  floorgrid::Random random(7);
  for (int s = 0; s < 32; ++s) {
    const Eigen::Vector2d p = map->free_points[static_cast<std::size_t>(
        random.integer(0, static_cast<std::int64_t>(map->free_points.size()) - 1))];
    floorgrid::LaserScan scan;
    scan.angle_increment = kPi / 360.0;
    scan.max_range = kMaxRange;
    scan.robot_pose = scan.laser_pose = {p.x(), p.y(), random.uniform(-kPi, kPi)};
    for (int k = 0; k < 361; ++k) {
      const double angle = scan.robot_pose.theta + scan.angle(static_cast<std::size_t>(k));
      scan.ranges.push_back(static_cast<float>(caster.cast(p, angle, kMaxRange)));
    }
    map->scans.push_back(floorgrid::make_observation(scan));
  }
  return map;
}

const BenchMap& office() {
  static const std::unique_ptr<BenchMap> map = make_simulated("office");
  return *map;
}

const BenchMap& warehouse() {
  static const std::unique_ptr<BenchMap> map = make_simulated("warehouse");
  return *map;
}

const BenchMap* fr079() {
  static const std::unique_ptr<BenchMap> map = make_fr079();
  return map.get();
}

/// `n` particles in random free cells with random headings (global localization's spread).
floorgrid::ParticleSet random_particles(const BenchMap& map, std::size_t n, bool with_scale) {
  floorgrid::Random random(3);
  floorgrid::ParticleSet particles;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = map.free_points[static_cast<std::size_t>(
        random.integer(0, static_cast<std::int64_t>(map.free_points.size()) - 1))];
    particles.x.push_back(p.x() + random.uniform(-0.025, 0.025));
    particles.y.push_back(p.y() + random.uniform(-0.025, 0.025));
    particles.theta.push_back(random.uniform(-kPi, kPi));
    if (with_scale)
      particles.scale.push_back(random.uniform(0.95, 1.05));
  }
  return particles;
}

/// Likelihood field, args (particles, threads, with scale): items = particle-beam evaluations,
/// end to end (one log_likelihood call per scan, threads started inside).
void BM_LikelihoodField(benchmark::State& state, const BenchMap* map) {
  const floorgrid::LikelihoodFieldModel model(map->grid);
  const floorgrid::ParticleSet particles =
      random_particles(*map, static_cast<std::size_t>(state.range(0)), state.range(2) != 0);
  const int threads = static_cast<int>(state.range(1));
  std::vector<double> out;
  std::size_t next = 0;
  std::int64_t evaluations = 0;
  for (auto _ : state) {
    const ScanObservation& scan = map->scans[next++ % map->scans.size()];
    model.log_likelihood(scan, particles, out, threads);
    benchmark::DoNotOptimize(out.data());
    evaluations += static_cast<std::int64_t>(particles.size() * scan.size());
  }
  state.SetItemsProcessed(evaluations);
}

/// Building the likelihood field's tables (distance transform, log table).
void BM_LikelihoodFieldBuild(benchmark::State& state, const BenchMap* map) {
  for (auto _ : state) {
    const floorgrid::LikelihoodFieldModel model(map->grid);
    benchmark::DoNotOptimize(&model);
  }
}

/// Random rays: origin in a random free cell, random direction, at most 30 m.
struct Ray {
  Eigen::Vector2d origin;
  double angle;
};

std::vector<Ray> random_rays(const BenchMap& map) {
  floorgrid::Random random(9);
  std::vector<Ray> rays(1 << 14);
  for (Ray& ray : rays) {
    ray.origin = map.free_points[static_cast<std::size_t>(
        random.integer(0, static_cast<std::int64_t>(map.free_points.size()) - 1))];
    ray.angle = random.uniform(-kPi, kPi);
  }
  return rays;
}

/// GridRayCaster::cast (metres, with its cos/sin): items = rays cast; counter mean_range_m.
void BM_GridRayCaster(benchmark::State& state, const BenchMap* map) {
  const floorgrid::GridRayCaster caster(map->grid);
  const std::vector<Ray> rays = random_rays(*map);
  std::size_t next = 0;
  double sum = 0.0;
  for (auto _ : state) {
    const Ray& ray = rays[next++ & (rays.size() - 1)];
    sum += caster.cast(ray.origin, ray.angle, kMaxRange);
  }
  // (benchmark 1.7's DoNotOptimize on a double corrupts it under GCC; the counter keeps sum.)
  state.SetItemsProcessed(state.iterations());
  state.counters["mean_range_m"] = sum / static_cast<double>(state.iterations());
}

/// GridRayCaster::cast_fan_in_cells: fans of 60 rays over 180 degrees from random free cells,
/// as the beam model casts a particle's beams; items = rays cast; counter mean_range_m.
void BM_GridRayCasterFan(benchmark::State& state, const BenchMap* map) {
  const floorgrid::GridRayCaster caster(map->grid);
  const floorgrid::GridGeometry& g = map->grid.geometry();
  const std::vector<Ray> origins = random_rays(*map);
  constexpr std::size_t kBeams = 60;
  std::vector<double> dx(kBeams), dy(kBeams), out(kBeams);
  std::size_t next = 0;
  double sum = 0.0;
  for (auto _ : state) {
    const Ray& ray = origins[next++ & (origins.size() - 1)];
    const Eigen::Vector2d c = g.to_cell_coordinates(ray.origin);
    for (std::size_t k = 0; k < kBeams; ++k) {
      const double a = ray.angle - g.origin.theta + kPi * (static_cast<double>(k) / 59.0 - 0.5);
      dx[k] = std::cos(a);
      dy[k] = std::sin(a);
    }
    caster.cast_fan_in_cells(c.x(), c.y(), dx.data(), dy.data(), kBeams, kMaxRange / g.resolution,
                             out.data());
    for (const double t : out)
      sum += t * g.resolution;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kBeams));
  state.counters["mean_range_m"] =
      sum / static_cast<double>(state.iterations() * static_cast<std::int64_t>(kBeams));
}

/// The plain cell walk (Amanatides-Woo, every cell tested) over the same rays, for comparison.
void BM_CellWalk(benchmark::State& state, const BenchMap* map) {
  const OccupancyGrid& grid = map->grid;
  const floorgrid::GridGeometry& g = grid.geometry();
  const std::vector<Ray> rays = random_rays(*map);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::size_t next = 0;
  double sum = 0.0;
  for (auto _ : state) {
    const Ray& ray = rays[next++ & (rays.size() - 1)];
    const Eigen::Vector2d c = g.to_cell_coordinates(ray.origin);
    const double a = ray.angle - g.origin.theta;
    const double dx = std::cos(a), dy = std::sin(a), max_cells = kMaxRange / g.resolution;
    int ix = static_cast<int>(c.x()), iy = static_cast<int>(c.y());
    const int sx = dx > 0 ? 1 : -1, sy = dy > 0 ? 1 : -1;
    double nx = dx > 0 ? (ix + 1 - c.x()) / dx : dx < 0 ? (ix - c.x()) / dx : kInf;
    double ny = dy > 0 ? (iy + 1 - c.y()) / dy : dy < 0 ? (iy - c.y()) / dy : kInf;
    const double ddx = 1.0 / std::abs(dx), ddy = 1.0 / std::abs(dy);
    double t = 0.0;
    bool left = false;
    while (t < max_cells && !grid.is_occupied(ix, iy)) {
      if (!g.contains(ix, iy)) {
        left = true;  // nothing blocks outside the grid
        break;
      }
      if (nx < ny) {
        t = nx;
        nx += ddx;
        ix += sx;
      } else {
        t = ny;
        ny += ddy;
        iy += sy;
      }
    }
    sum += left ? kMaxRange : std::min(t, max_cells) * g.resolution;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["mean_range_m"] = sum / static_cast<double>(state.iterations());
}

/// Building the ray caster's clearance field.
void BM_GridRayCasterBuild(benchmark::State& state, const BenchMap* map) {
  for (auto _ : state) {
    const floorgrid::GridRayCaster caster(map->grid);
    benchmark::DoNotOptimize(&caster);
  }
}

/// Beam model, args (particles, threads): items = particles scored (60 ray casts and mixture
/// terms each); counter beams_per_second.
void BM_BeamModel(benchmark::State& state, const BenchMap* map) {
  const floorgrid::BeamModel model(map->grid);
  const floorgrid::ParticleSet particles =
      random_particles(*map, static_cast<std::size_t>(state.range(0)), false);
  const int threads = static_cast<int>(state.range(1));
  std::vector<double> out;
  std::size_t next = 0;
  double beams = 0.0;
  for (auto _ : state) {
    const ScanObservation& scan = map->scans[next++ % map->scans.size()];
    model.log_likelihood(scan, particles, out, threads);
    benchmark::DoNotOptimize(out.data());
    beams += static_cast<double>(particles.size() * scan.size());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["beams_per_second"] = benchmark::Counter(beams, benchmark::Counter::kIsRate);
}

void register_map(const BenchMap* map) {
  const std::string m = "/" + map->name;
  benchmark::RegisterBenchmark(("LikelihoodField" + m).c_str(), BM_LikelihoodField, map)
      ->ArgNames({"particles", "threads", "scale"})
      ->ArgsProduct({{2000, 4000}, {1, 2}, {0}})
      ->Args({4000, 2, 1})
      ->UseRealTime()
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("LikelihoodFieldBuild" + m).c_str(), BM_LikelihoodFieldBuild, map)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("GridRayCaster" + m).c_str(), BM_GridRayCaster, map);
  benchmark::RegisterBenchmark(("GridRayCasterFan" + m).c_str(), BM_GridRayCasterFan, map);
  benchmark::RegisterBenchmark(("CellWalk" + m).c_str(), BM_CellWalk, map);
  benchmark::RegisterBenchmark(("GridRayCasterBuild" + m).c_str(), BM_GridRayCasterBuild, map)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("BeamModel" + m).c_str(), BM_BeamModel, map)
      ->ArgNames({"particles", "threads"})
      ->ArgsProduct({{2000, 4000}, {1, 2}})
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  register_map(&office());
  register_map(&warehouse());
  if (const BenchMap* map = fr079())
    register_map(map);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
