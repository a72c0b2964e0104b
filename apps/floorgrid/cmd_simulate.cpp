// `floorgrid simulate --preset P --seed N --out DIR [--preview]`: a synthetic dataset with exact
// ground truth; `floorgrid simulate --from-log LOG [--plan-scale S] [--bend M] [--rotation DEG]
// [--plan-format png|dxf] [--dxf-units U] [--dxf-header H] --seed N --out DIR`: a semi-real one
// from a corrected real log.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/io/robot_log_reader.hpp"
#include "floorgrid/io/simulation_writer.hpp"
#include "floorgrid/simulation/log_dataset.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid::app {

namespace {

template <class Args>
void simulate_log_dataset(const Args& a) {
  const auto start = std::chrono::steady_clock::now();
  LogDatasetOptions options;
  options.seed = a.seed;
  options.plan_scale = a.plan_scale;
  options.bend = a.bend;
  options.rotation_deg = a.rotation;
  options.vector_plan = a.plan_format == "dxf";
  options.drawing_units = a.dxf_units;
  options.header_units = a.dxf_header.value_or(a.dxf_units);
  try {
    validate_log_dataset_options(options);
  } catch (const InputError& e) {
    std::string option = e.field();
    std::replace(option.begin(), option.end(), '_', '-');
    throw InputError(e.message(), "", 0, "--" + option);
  }
  const io::OutputFolder out_folder(a.out);
  spdlog::info("reading {}", a.from_log);
  const io::ReadRobotLog log = io::read_robot_log(a.from_log);
  for (const std::string& warning : log.summary.warnings)
    spdlog::warn("{}: {}", a.from_log, warning);
  spdlog::info("mapping {} scans and drawing the plan (seed {})", log.scans.size(), a.seed);
  const LogDataset d = [&] {
    try {
      return simulate_from_log(log, options);
    } catch (const InputError& e) {
      if (!e.file().empty())
        throw;
      // What the log cannot give is the log's fault: name it, and what its reader skipped.
      std::size_t skipped = 0;
      for (const auto& [type, count] : log.summary.messages)
        skipped += count.skipped_backwards_timestamp + count.skipped_zero_timestamp;
      const std::string note =
          skipped > 0 ? " (" + std::to_string(skipped) +
                            " messages were skipped as out of time order or without a time)"
                      : "";
      throw InputError(e.message() + note, a.from_log, 0, e.field());
    }
  }();
  const auto files = io::write_log_dataset(d, a.from_log, a.out, a.preview);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const LogDatasetStatistics& s = d.statistics;
  const LogDatasetOptions& o = d.options;
  fmt::print("from {} seed {}\n", a.from_log, o.seed);
  fmt::print("  run       {} scans over {:.0f} m: median step {:.2f} m and {:.1f} deg\n", s.scans,
             s.path_length, s.median_step, s.median_turn_deg);
  fmt::print("  gridmap   {} x {} cells at {} m: {} occupied, {} free\n", d.gridmap.width(),
             d.gridmap.height(), d.gridmap.resolution(), s.occupied_cells, s.free_cells);
  fmt::print(
      "  plan      {} ({} x {} px), true floorplan_scale {:.4f} (plan {:.4f} m per px), "
      "turned {:.1f} deg, walls {} px; {} occupied cells left out as clutter\n",
      o.vector_plan ? fmt::format("DXF in {} under a header saying {}, {} segments",
                                  o.drawing_units, o.header_units, s.plan_segments)
                    : "raster",
      d.plan_raster.width(), d.plan_raster.height(), *o.plan_scale, d.plan_raster.resolution(),
      s.rotation_deg, s.wall_thickness_px, s.clutter_cells);
  fmt::print(
      "  warp      bend {:.2f} m (max strain {:.2f}%); the best global fit's floorplan_scale "
      "{:.4f} ({:+.3f}%)\n",
      s.bend_deviation, 100.0 * s.max_bend_strain, *o.plan_scale * s.warp_fit_scale,
      100.0 * (s.warp_fit_scale - 1.0));
  fmt::print("  pairs     {} manual pairs\n", d.manual_pairs.size());
  fmt::print("wrote {} files to {} in {:.1f} s\n", files.files.size(), files.folder.string(),
             seconds);
}

}  // namespace

void add_simulate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("simulate", "A synthetic dataset with exact ground truth");
  struct Args {
    std::string preset = "office";
    std::uint64_t seed = 1;
    std::string out;
    bool preview = false;
    std::string from_log;
    std::optional<double> plan_scale, bend, rotation;
    std::string plan_format = "png";
    std::string dxf_units = "m";
    std::optional<std::string> dxf_header;
  };
  auto args = std::make_shared<Args>();
  std::string presets;
  for (const auto& n : simulation_preset_names())
    presets += (presets.empty() ? "" : ", ") + n;
  auto* preset = cmd->add_option("--preset", args->preset, "building preset: " + presets)
                     ->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed: the same seed gives the same dataset")
      ->check(seed_check())
      ->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->required();
  cmd->add_flag("--preview", args->preview,
                "also write preview.png: the gridmap with the plan's walls through the exact warp");
  auto* from_log =
      cmd->add_option(
             "--from-log", args->from_log,
             "a corrected log (CARMEN, .gz allowed, or a ROS bag/MCAP/rosbag2 whose odometry "
             "is the corrected trajectory): make a semi-real dataset "
             "from it instead of a preset")
          ->excludes(preset);
  const auto needs_log = [&](CLI::Option* option) { option->needs(from_log); };
  needs_log(cmd->add_option("--plan-scale", args->plan_scale,
                            "from a log: the plan's true floorplan_scale (world m per plan m); "
                            "default: log-uniform in 0.5-2 by the seed"));
  needs_log(cmd->add_option("--bend", args->bend,
                            "from a log: metres the far end of the long axis bends; default: "
                            "0.2-1 by the seed"));
  needs_log(cmd->add_option("--rotation", args->rotation,
                            "from a log: degrees the plan is turned; default: any, by the seed"));
  needs_log(cmd->add_option("--plan-format", args->plan_format,
                            "from a log: png (a raster with a map YAML) or dxf (vector walls)")
                ->check(CLI::IsMember({"png", "dxf"}))
                ->capture_default_str());
  needs_log(cmd->add_option("--dxf-units", args->dxf_units,
                            "from a log, DXF plan: the unit its coordinates are in")
                ->check(CLI::IsMember({"m", "cm", "mm", "in", "ft"}))
                ->capture_default_str());
  needs_log(cmd->add_option("--dxf-header", args->dxf_header,
                            "from a log, DXF plan: what its $INSUNITS says, or none (no header); "
                            "default: the --dxf-units")
                ->check(CLI::IsMember({"none", "m", "cm", "mm", "in", "ft"})));
  cmd->callback([args] {
    if (!args->from_log.empty()) {
      simulate_log_dataset(*args);
      return;
    }
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
