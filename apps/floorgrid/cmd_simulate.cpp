// `floorgrid simulate --preset P --seed N --out DIR [--preview]`: a synthetic dataset with exact
// ground truth.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/io/simulation_writer.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid::app {

void add_simulate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("simulate", "A synthetic dataset with exact ground truth");
  struct Args {
    std::string preset = "office";
    std::uint64_t seed = 1;
    std::string out;
    bool preview = false;
  };
  auto args = std::make_shared<Args>();
  std::string presets;
  for (const auto& n : simulation_preset_names())
    presets += (presets.empty() ? "" : ", ") + n;
  cmd->add_option("--preset", args->preset, "building preset: " + presets)->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed: the same seed gives the same dataset")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->required();
  cmd->add_flag("--preview", args->preview,
                "also write preview.png: the gridmap with the plan's walls through the exact warp");
  cmd->callback([args] {
    const auto start = std::chrono::steady_clock::now();
    // Fail on a bad preset or an unusable folder before the work, not after.
    simulation_preset(args->preset);
    const io::OutputFolder out_folder(args->out);
    spdlog::info("simulating preset {} seed {}", args->preset, args->seed);
    const SimulatedDataset d = simulate(args->preset, args->seed);
    const auto files = io::write_simulated_dataset(d, args->out, args->preview);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SimulationStatistics& s = d.statistics;
    fmt::print("{} seed {}: {} rooms ({} visited), {:.0f} x {:.0f} m\n", d.preset.name, d.seed,
               s.rooms, s.rooms_visited, d.building.outline.sizes().x(),
               d.building.outline.sizes().y());
    fmt::print("  run       {:.0f} m in {:.0f} s, {} scans, {:.1f}% of {} beams hit furniture\n",
               s.path_length, s.duration, s.scans, 100.0 * s.furniture_fraction, s.beams);
    fmt::print("  odometry  drifts {:.2f} m by the end\n", s.final_odometry_error);
    fmt::print("  plan      scale {:.4f}, drawn in {} under a header saying {}\n", d.plan_scale,
               d.preset.drawing_units, d.preset.header_units);
    fmt::print("  gridmap   {} x {} cells: {} occupied, {} free, {} unknown\n", d.gridmap.width(),
               d.gridmap.height(), s.occupied_cells, s.free_cells, s.unknown_cells);
    fmt::print("  warp      bend {:.2f} m (max strain {:.2f}%), room rotated {:.2f} deg\n",
               s.bend_deviation, 100.0 * s.max_bend_strain, s.room_rotation_deg);
    fmt::print("  pairs     {} manual pairs\n", d.manual_pairs.size());
    fmt::print("wrote {} files to {} in {:.1f} s\n", files.files.size(), files.folder.string(),
               seconds);
  });
}

}  // namespace floorgrid::app
