// Reader throughput on the real files in ../shared/data (skipped when absent).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/maps/rasterize.hpp"

namespace {

std::filesystem::path data(const char* relative) {
  return std::filesystem::path(FLOORGRID_DATA_DIR) / relative;
}

bool require(benchmark::State& state, const std::filesystem::path& path) {
  if (std::filesystem::exists(path))
    return true;
  state.SkipWithError(("shared data missing: " + path.string()).c_str());
  return false;
}

void BM_ReadCarmenFr079(benchmark::State& state) {
  const auto path = data("fr079/freiburg-079-corrected.log.gz");
  if (!require(state, path))
    return;
  std::size_t scans = 0;
  for (auto _ : state) {
    const auto log = floorgrid::io::read_carmen(path);
    scans = log.scans.size();
    benchmark::DoNotOptimize(scans);
  }
  state.counters["scans"] = static_cast<double>(scans);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(scans));
}
BENCHMARK(BM_ReadCarmenFr079)->Unit(benchmark::kMillisecond);

void BM_ReadDxfHouseSite(benchmark::State& state) {
  const auto path = data("dxf/house_site_r2000.dxf");
  if (!require(state, path))
    return;
  for (auto _ : state) {
    const auto plan = floorgrid::io::read_dxf(path);
    benchmark::DoNotOptimize(plan.plan.segments().size());
  }
}
BENCHMARK(BM_ReadDxfHouseSite)->Unit(benchmark::kMillisecond);

void BM_ReadMapYouBot(benchmark::State& state) {
  const auto path = data("bonn/2021_10_27/YouBotMap.yaml");
  if (!require(state, path))
    return;
  for (auto _ : state) {
    const auto map = floorgrid::io::read_map_yaml(path);
    benchmark::DoNotOptimize(map.grid.width());
  }
}
BENCHMARK(BM_ReadMapYouBot)->Unit(benchmark::kMillisecond);

void BM_RasterizeHouseSite(benchmark::State& state) {
  const auto path = data("dxf/house_site_r2000.dxf");
  if (!require(state, path))
    return;
  const auto plan = floorgrid::io::read_dxf(path).plan;
  floorgrid::RasterizeOptions options;
  options.resolution = 0.05;
  std::size_t cells = 0;
  for (auto _ : state) {
    const auto grid = floorgrid::rasterize(plan, options);
    cells = grid.geometry().size();
    benchmark::DoNotOptimize(cells);
  }
  state.counters["cells"] = static_cast<double>(cells);
}
BENCHMARK(BM_RasterizeHouseSite)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
