// Heat maps of a 4,000 x 4,000 cell domain (200 x 200 m at 5 cm), every cell evaluated through
// the model's own batch (targets: <= 2 s for gt, dt and tps, <= 5 s for gp on this 2-core
// machine), and the uncertainty map (std_m) of the same raster.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "floorgrid/core/random.hpp"
#include "floorgrid/evaluation/heat_map.hpp"
#include "floorgrid/mapping/error_model.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace {

using namespace floorgrid;

constexpr int kSide = 4000;           // cells
constexpr double kResolution = 0.05;  // metres

// A SLAM-like distortion: rotation, shift, a 1 m bend over the 200 m.
Eigen::Vector2d warp(const Eigen::Vector2d& p) {
  const double c = std::cos(0.2), s = std::sin(0.2);
  const Eigen::Vector2d bent(p.x(), p.y() + 1.0 * std::sin(p.x() / 64.0));
  return Eigen::Vector2d(c * bent.x() - s * bent.y() + 12.0, s * bent.x() + c * bent.y() - 7.0);
}

/// Laser-like pairs along the walls of 10 m rooms over the 200 m square, 2 cm of noise.
ReferencePairs wall_pairs() {
  Random random(7);
  ReferencePairs pairs;
  const int count = 40000;
  pairs.points_in_plan.resize(2, count);
  pairs.points_in_grid.resize(2, count);
  for (int i = 0; i < count; ++i) {
    const double along = random.uniform(0.0, 200.0);
    const double wall = 10.0 * std::floor(random.uniform(0.0, 21.0));
    const Eigen::Vector2d p =
        i % 2 == 0 ? Eigen::Vector2d(along, wall) : Eigen::Vector2d(wall, along);
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) =
        warp(p) + Eigen::Vector2d(random.normal(0.02), random.normal(0.02));
  }
  return pairs;
}

const PointMapping& model(const std::string& name) {
  static std::map<std::string, std::unique_ptr<PointMapping>> cache;
  std::unique_ptr<PointMapping>& slot = cache[name];
  if (!slot) {
    MappingOptions options;
    options.model = name;
    slot = make_mapping(options);
    slot->fit(wall_pairs());
    ErrorModel e;  // as align's cross-validation would set it
    e.base_std_m = 0.02;
    e.growth = 0.05;
    slot->set_error_model(e);
  }
  return *slot;
}

GridGeometry raster() {
  GridGeometry g;
  g.width = kSide;
  g.height = kSide;
  g.resolution = kResolution;
  return g;
}

void BM_ErrorHeatMap(benchmark::State& state, const std::string& name) {
  const PointMapping& m = model(name);
  const GridGeometry g = raster();
  const CellMask all(g.size(), 1);
  const PlanToGridBatch truth = [](const Eigen::Ref<const Eigen::Matrix2Xd>& points) {
    Eigen::Matrix2Xd out(2, points.cols());
    for (Eigen::Index i = 0; i < points.cols(); ++i)
      out.col(i) = warp(points.col(i));
    return out;
  };
  HeatMap map;
  double first_s = -1.0;
  for (auto _ : state) {
    map = error_heat_map(m, truth, g, all);
    benchmark::DoNotOptimize(map.values.data());
    if (first_s < 0.0)
      first_s = map.seconds;
  }
  state.counters["cells"] = static_cast<double>(map.known());
  state.counters["p95_error_m"] = map.quantile(0.95);
  // The first map builds what the model builds on first use (tps: its lattice).
  state.counters["first_s"] = first_s;
  // What mapping the cells in batches adds to the model's own forward() (tps: its lattice's
  // error), the largest over 20,000 random cells, metres.
  Random random(11);
  double added = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const auto ix = static_cast<int>(random.integer(0, kSide - 1));
    const auto iy = static_cast<int>(random.integer(0, kSide - 1));
    const Eigen::Vector2d p = g.cell_center(ix, iy);
    const double exact = (m.forward(p) - warp(p)).norm();
    added =
        std::max(added, std::abs(exact - map.values[static_cast<std::size_t>(iy) * kSide + ix]));
  }
  state.counters["added_max_m"] = added;
}

void BM_UncertaintyMap(benchmark::State& state, const std::string& name) {
  const PointMapping& m = model(name);
  const GridGeometry g = raster();
  const CellMask all(g.size(), 1);
  HeatMap map;
  for (auto _ : state) {
    map = uncertainty_map(m, g, all);
    benchmark::DoNotOptimize(map.values.data());
  }
  state.counters["cells"] = static_cast<double>(map.known());
}

}  // namespace

BENCHMARK_CAPTURE(BM_ErrorHeatMap, gt, std::string("gt"))->Unit(benchmark::kSecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_ErrorHeatMap, dt, std::string("dt"))->Unit(benchmark::kSecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_ErrorHeatMap, tps, std::string("tps"))
    ->Unit(benchmark::kSecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_ErrorHeatMap, gp, std::string("gp"))->Unit(benchmark::kSecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_UncertaintyMap, gp, std::string("gp"))
    ->Unit(benchmark::kSecond)
    ->Iterations(2);

BENCHMARK_MAIN();
