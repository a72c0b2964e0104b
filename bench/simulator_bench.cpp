// End to end: `floorgrid simulate` in memory and with its files, per preset.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace {

const char* kPresets[] = {"office", "warehouse", "bent-office", "office-inches"};

void BM_Simulate(benchmark::State& state) {
  const char* preset = kPresets[state.range(0)];
  state.SetLabel(preset);
  std::size_t scans = 0;
  for (auto _ : state) {
    const auto d = floorgrid::simulate(preset, 1);
    scans = d.log.scans.size();
    benchmark::DoNotOptimize(scans);
  }
  state.counters["scans"] = static_cast<double>(scans);
}
BENCHMARK(BM_Simulate)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_SimulateAndWrite(benchmark::State& state) {
  const char* preset = kPresets[state.range(0)];
  state.SetLabel(preset);
  const auto folder = std::filesystem::temp_directory_path() / "floorgrid-bench-simulate";
  for (auto _ : state) {
    const auto d = floorgrid::simulate(preset, 1);
    floorgrid::io::write_simulated_dataset(d, folder, true);
  }
  std::filesystem::remove_all(folder);
}
BENCHMARK(BM_SimulateAndWrite)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
