// `floorgrid simulate --preset P [--duration SECONDS] --seed N --out DIR [--preview]`: a synthetic
// dataset with exact ground truth; `floorgrid simulate --from-log LOG [--plan-scale S] [--bend M]
// [--rotation DEG] [--plan-format png|dxf] [--dxf-units U] [--dxf-header H] --seed N --out DIR`:
// a semi-real one from a corrected real log; `floorgrid simulate --from-plan PLAN [--resolution R]
// [--origin x,y,yaw] [--plan-scale S] [--bend M] [--rotation DEG] [--drawing-errors none|some]
// --seed N --out DIR`: a world built from a real drawing, a run through it and its SLAM-like map.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/plan_dataset_writer.hpp"
#include "floorgrid/io/dataset/robot_log_reader.hpp"
#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/plans/plan_drawing.hpp"
#include "floorgrid/simulation/log_dataset.hpp"
#include "floorgrid/simulation/plan_dataset.hpp"
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

// Where the world differs from the drawing, in plan metres.
std::string describe_errors(const PlanDataset& d) {
  std::string text;
  const double to_plan = 1.0 / d.statistics.plan_scale;
  for (const DrawingError& e : d.world.errors) {
    const Eigen::Vector2d a = e.a * to_plan, b = e.b * to_plan;
    text += fmt::format("{}{} {:.2f} m at ({:.2f}, {:.2f})-({:.2f}, {:.2f})",
                        text.empty() ? "" : "; ", e.kind, e.amount, a.x(), a.y(), b.x(), b.y());
  }
  return text.empty() ? "none" : text;
}

template <class Args>
void simulate_plan_dataset(const Args& a) {
  const auto start = std::chrono::steady_clock::now();
  PlanDatasetOptions options;
  options.seed = a.seed;
  options.plan_scale = a.plan_scale;
  options.bend = a.bend;
  options.rotation_deg = a.rotation;
  options.drawing_errors = a.drawing_errors == "some";
  try {
    validate_plan_dataset_options(options);
  } catch (const InputError& e) {
    std::string option = e.field();
    std::replace(option.begin(), option.end(), '_', '-');
    throw InputError(e.message(), "", 0, "--" + option);
  }
  std::optional<Pose2> origin;
  if (!a.origin.empty())
    origin = parse_pose(a.origin, "--origin");
  const io::OutputFolder out_folder(a.out);
  spdlog::info("reading {}", a.from_plan);
  const io::PlanDrawingFile drawing = io::read_plan_drawing(a.from_plan, a.resolution, origin);
  for (const std::string& warning : drawing.warnings)
    spdlog::warn("{}: {}", a.from_plan, warning);
  spdlog::info("building the world, driving and mapping it (seed {})", a.seed);
  PlanDataset d;
  try {
    d = simulate_from_plan(drawing.drawing, options);
  } catch (const InputError& e) {
    // The drawing itself is at fault: say which file.
    if (e.field() != "plan")
      throw;
    throw InputError(e.message(), a.from_plan, 0, "--from-plan");
  }
  const auto files = io::write_plan_dataset(d, drawing, a.out, a.preview);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PlanDatasetStatistics& s = d.statistics;
  const PlanWorld& w = d.world;
  std::size_t rooms = 0, corridors = 0, halls = 0;
  for (const WorldRegion& r : w.regions) {
    rooms += r.kind == "room";
    corridors += r.kind == "corridor";
    halls += r.kind == "hall";
  }
  const double beams = std::max<double>(1.0, double(s.beams));
  fmt::print("from {} seed {}\n", a.from_plan, d.options.seed);
  fmt::print(
      "  drawing   {}{}\n",
      drawing.kind == "dxf"
          ? fmt::format("DXF in {} (header says {}), {} segments and {} arcs",
                        drawing.dxf->units_used, drawing.dxf->header_units,
                        drawing.drawing.vector.segments().size(),
                        drawing.drawing.vector.arcs().size())
          : fmt::format("raster {} x {} px at {} m per px", drawing.drawing.raster->width(),
                        drawing.drawing.raster->height(), drawing.drawing.raster->resolution()),
      drawing.layers.empty() ? ""
                             : ", layers " + fmt::format("{}", fmt::join(drawing.layers, " ")));
  fmt::print(
      "  world     walls {:.2f} m (partitions) and {:.2f} m (exterior) on a {} m raster; "
      "{} regions ({} rooms, {} corridors, {} halls)\n",
      w.partition_thickness, w.exterior_thickness, s.raster_resolution, w.regions.size(), rooms,
      corridors, halls);
  fmt::print(
      "            {} doors open, {} closed, {} doorways without a leaf; {} glass walls "
      "({} mullions); {} columns; {} pieces of furniture\n",
      w.doors_in_state("open"), w.doors_in_state("closed"), w.doors_in_state("none"),
      w.glass.size(), w.count(SurfaceKind::mullion), w.count(SurfaceKind::column),
      w.count(SurfaceKind::furniture));
  fmt::print("  errors    {}\n", describe_errors(d));
  fmt::print(
      "  run       {:.0f} m in {:.0f} s, {} scans; regions visited {} of {} ({} left out, "
      "{} out of reach)\n",
      s.path_length, s.duration, s.scans, d.tour.visited.size(), w.regions.size(),
      d.tour.skipped.size(), d.tour.unreachable.size());
  fmt::print(
      "  beams     {:.1f}% walls, {:.1f}% furniture, {:.1f}% doors, {:.1f}% columns and "
      "mullions ({:.1f}% clutter and doors, as the presets count) of {}\n",
      100.0 * s.wall_beams / beams, 100.0 * s.furniture_beams / beams, 100.0 * s.door_beams / beams,
      100.0 * s.column_beams / beams, 100.0 * s.clutter_fraction, s.beams);
  fmt::print("  odometry  drifts {:.2f} m by the end\n", s.final_odometry_error);
  fmt::print(
      "  plan      true floorplan_scale {:.4f} (drawn from {:.2f}-{:.2f}), gridmap turned "
      "{:.1f} deg\n",
      s.plan_scale, s.plan_scale_low, d.options.max_plan_scale, s.rotation_deg);
  fmt::print("  gridmap   {} x {} cells at {} m: {} occupied, {} free, {} unknown\n",
             d.gridmap.width(), d.gridmap.height(), d.gridmap.resolution(), s.occupied_cells,
             s.free_cells, s.unknown_cells);
  fmt::print(
      "  warp      bend {:.2f} m (max strain {:.2f}%), a room turned {:.2f} deg; the best "
      "global fit's floorplan_scale {:.4f} ({:+.3f}%)\n",
      s.bend_deviation, 100.0 * s.max_bend_strain, s.room_rotation_deg,
      s.plan_scale * s.warp_fit_scale, 100.0 * (s.warp_fit_scale - 1.0));
  fmt::print("  pairs     {} manual pairs\n", d.manual_pairs.size());
  fmt::print("wrote {} files to {} in {:.1f} s\n", files.files.size(), files.folder.string(),
             seconds);
}

}  // namespace

void add_simulate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("simulate", "A synthetic dataset with exact ground truth");
  struct Args {
    std::string preset = "office";
    std::optional<double> duration;
    std::uint64_t seed = 1;
    std::string out;
    bool preview = false;
    std::string from_log;
    std::optional<double> plan_scale, bend, rotation;
    std::string plan_format = "png";
    std::string dxf_units = "m";
    std::optional<std::string> dxf_header;
    std::string from_plan;
    std::optional<double> resolution;
    std::string origin;
    std::string drawing_errors = "none";
  };
  auto args = std::make_shared<Args>();
  std::string presets;
  for (const auto& n : simulation_preset_names())
    presets += (presets.empty() ? "" : ", ") + n;
  auto* preset = cmd->add_option("--preset", args->preset, "building preset: " + presets)
                     ->capture_default_str();
  const SimulationOptions simulation_defaults;
  auto* duration =
      cmd->add_option("--duration", args->duration,
                      fmt::format("seconds of driving (at most {:g}): the preset's tour driven "
                                  "over and over, forth and back, until then, {:g} scans a "
                                  "second; default: the tour once, 5 scans a second",
                                  simulation_defaults.max_duration, simulation_defaults.scan_rate));
  cmd->add_option("--seed", args->seed, "random seed: the same seed gives the same dataset")
      ->check(seed_check())
      ->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->required();
  cmd->add_flag("--preview", args->preview,
                "also write preview.png: the gridmap with the plan's walls through the exact warp "
                "(and, from a drawing, world.png: the world built, its tour and its errors)");
  auto* from_log =
      cmd->add_option(
             "--from-log", args->from_log,
             "a corrected log (CARMEN, .gz allowed, or a ROS bag/MCAP/rosbag2 whose odometry "
             "is the corrected trajectory): make a semi-real dataset "
             "from it instead of a preset")
          ->excludes(preset)
          ->excludes(duration);
  auto* from_plan =
      cmd->add_option("--from-plan", args->from_plan,
                      "a real drawing (a map YAML, a PNG/PGM image with --resolution, or a "
                      "DXF): build a world from it (walls of real thickness, doors, glass, "
                      "columns, furniture the drawing lacks), drive a robot through it and map "
                      "it with drift")
          ->excludes(preset)
          ->excludes(duration)
          ->excludes(from_log);
  const auto needs_log = [&](CLI::Option* option) { option->needs(from_log); };
  const auto needs_plan = [&](CLI::Option* option) { option->needs(from_plan); };
  // Shared by --from-log and --from-plan (checked in the callback: CLI11 needs one option).
  const PlanDatasetOptions plan_defaults;
  auto* plan_scale = cmd->add_option(
      "--plan-scale", args->plan_scale,
      fmt::format("from a log or a drawing: the plan's true floorplan_scale (world m per plan m); "
                  "default: log-uniform in {}-{} by the seed (a DXF drawing's lower end raised "
                  "so that its doorways stay {} m wide)",
                  plan_defaults.min_plan_scale, plan_defaults.max_plan_scale,
                  plan_defaults.min_doorway));
  auto* bend =
      cmd->add_option("--bend", args->bend,
                      fmt::format("from a log or a drawing: metres the far end of the "
                                  "long axis bends; default: {}-{} by the seed",
                                  plan_defaults.bend_range.min, plan_defaults.bend_range.max));
  auto* rotation = cmd->add_option("--rotation", args->rotation,
                                   "from a log or a drawing: degrees the plan is turned against "
                                   "the gridmap; default: any, by the seed");
  needs_plan(cmd->add_option("--resolution", args->resolution,
                             "from a drawing that is a bare image: metres per pixel")
                 ->check(CLI::PositiveNumber));
  needs_plan(cmd->add_option("--origin", args->origin,
                             "from a drawing that is a bare image: origin x,y,yaw (metres, "
                             "radians; default 0,0,0)"));
  needs_plan(cmd->add_option("--drawing-errors", args->drawing_errors,
                             fmt::format("from a drawing: some = the world differs from it in "
                                         "three places (a partition moved {}-{} m, one added or "
                                         "removed, a door shifted {}-{} m along its wall); none = "
                                         "built as drawn",
                                         plan_defaults.world.partition_shift.min,
                                         plan_defaults.world.partition_shift.max,
                                         plan_defaults.world.door_shift.min,
                                         plan_defaults.world.door_shift.max))
                 ->check(CLI::IsMember({"none", "some"}))
                 ->capture_default_str());
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
  cmd->callback([args, plan_scale, bend, rotation] {
    if (!args->from_plan.empty()) {
      simulate_plan_dataset(*args);
      return;
    }
    if (!args->from_log.empty()) {
      simulate_log_dataset(*args);
      return;
    }
    for (const CLI::Option* option : {plan_scale, bend, rotation}) {
      if (option->count() > 0)
        throw InputError("needs --from-log or --from-plan", "", 0, option->get_name());
    }
    const auto start = std::chrono::steady_clock::now();
    // Fail on a bad preset, duration or an unusable folder before the work, not after.
    simulation_preset(args->preset);
    SimulationOptions options;
    options.duration = args->duration;
    try {
      validate(options);
    } catch (const InputError& e) {
      throw InputError(e.message(), "", 0, "--" + e.field());
    }
    const io::OutputFolder out_folder(args->out);
    spdlog::info("simulating preset {} seed {}{}", args->preset, args->seed,
                 args->duration ? fmt::format(" for {:g} s", *args->duration) : "");
    const SimulatedDataset d = simulate(args->preset, args->seed, options);
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
