// `floorgrid align DATASET --out DIR`: pairs, every model fitted and judged, overlays, metrics.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/dataset_run.hpp"
#include "apps/floorgrid/job_options.hpp"
#include "apps/floorgrid/progress.hpp"
#include "apps/floorgrid/summaries.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/alignment_writer.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/io/dataset_loader.hpp"
#include "floorgrid/io/export_bundle.hpp"
#include "floorgrid/io/export_inputs.hpp"
#include "floorgrid/io/report_html.hpp"

namespace floorgrid::app {

namespace {

/// The chosen model in other tools' terms, into DIR/exports (after the alignment was accepted:
/// a rejected one is not worth exporting). A failure here costs the exports, not the job.
void write_align_exports(const Alignment& a, const io::LoadedDataset& d,
                         const std::filesystem::path& out) {
  const PointMapping* chosen = nullptr;
  for (const ModelAlignment& m : a.models) {
    if (m.report.name == "auto" && m.report.model)
      chosen = m.report.model.get();
  }
  if (!chosen)
    return;
  const auto start = std::chrono::steady_clock::now();
  try {
    const io::ExportFiles files =
        io::write_exports(*chosen, a.localization.pairs, io::export_maps(d), out / "exports");
    for (const std::string& skipped : files.skipped)
      spdlog::info("export skipped: {}", skipped);
    fmt::print(
        "exports     {} files in {} ({:.2f} s; `floorgrid export --help` says what "
        "each is)\n",
        files.files.size(), (out / "exports").string(),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const InputError& e) {
    spdlog::warn("exports not written: {}", e.what());
  }
}

}  // namespace

void run_align(const std::string& dataset, const std::string& out, const JobOptions& options) {
  const io::OutputFolder out_folder(out);
  const auto load_start = std::chrono::steady_clock::now();
  const io::LoadedDataset d =
      io::load_dataset(dataset, options.raster, options.limits, options.units);
  report_loading(d);
  io::AlignmentTimings timings;
  timings.load =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  // Without a log (or without using it) the pairs come from the maps alone.
  const AlignmentInputs inputs{d.plan_grid,
                               d.plan ? &*d.plan : nullptr,
                               d.plan_wall_samples,
                               d.gridmap,
                               dataset_log_or_none(d, options.align.pairs_from != PairSource::maps),
                               start_poses(d),
                               d.manifest.floorplan_scale,
                               warp_truth(d),
                               d.manual_pairs ? &*d.manual_pairs : nullptr};
  ProgressLine progress;
  const Alignment a = align(inputs, options.align, [&](const AlignmentProgress& p) {
    progress.update(p.stage == "fit" ? "fit " + p.detail : p.detail, p.done, p.total);
  });
  progress.finish();
  require_localized(a.localization.status, d);
  print_localization(a.localization, a.pair_errors, a.pairs_from);
  if (a.wall_slide)
    print_wall_slide(*a.wall_slide, static_cast<std::size_t>(a.localization.pairs.size()),
                     a.localized_pair_errors);
  if (a.pair_noise) {
    fmt::print(
        "pair noise  {:.3f} m rms, from {} differences between visits to one place "
        "(taken out of each model's std_m)\n",
        std::sqrt(a.pair_noise->mean_square_m2), a.pair_noise->differences);
  }
  if (a.plan_match.judged) {
    fmt::print(
        "plan match  score {:.2f} under the pairs' similarity ({:.0f}% of the gridmap's "
        "walls on the plan's, {:.0f}% of the plan's walls in free space)\n",
        a.plan_match.score.score, 100.0 * a.plan_match.score.on_walls,
        100.0 * a.plan_match.score.in_free_space);
  }
  print_models(a);
  const std::string name = d.manifest.display_name();
  // From here files are written: the folder says it is incomplete until the last one is.
  io::IncompleteMarker incomplete(out, "floorgrid align");
  const io::AlignmentFiles files = io::write_alignment(
      a, inputs, name, out, timings, io::floorplan_units_json(d), d.manifest.manifest_path);
  fmt::print("\nwrote {} files to {} (metrics.json, model.json, overlays/)\n", files.files.size(),
             files.folder.string());
  // What was learnt is written (metrics.json holds the localization's story), but a run that
  // made no pairs is a failure, not a result; its report still tells what happened.
  try {
    require_pairs(a.localization, d);
    // Pairs from the maps alone were judged by the maps' own fitness (require_localized).
    if (a.pairs_from != PairSource::maps)
      require_plan_match(a.plan_match, d, options.align.localization.plan_location);
  } catch (...) {
    write_report(out);
    incomplete.done();
    throw;
  }
  write_align_exports(a, d, out);
  write_report(out);
  incomplete.done();
}

void add_align_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "align", "The main job: pairs, every model fitted and judged, overlays and metrics");
  struct Args {
    std::string dataset, out;
    std::optional<std::string> pairs_from;
    bool maps_only = false;
  };
  auto args = std::make_shared<Args>();
  auto job = std::make_shared<JobArgs>();
  cmd->add_option("DATASET", args->dataset, "dataset.yaml or its folder")->required();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->required();
  cmd->add_option("--pairs-from", args->pairs_from,
                  "where the pairs come from: the robot's run (run, the default with a log), "
                  "the two maps alone (maps: registered, then bent onto each other; the "
                  "default without a log) or both")
      ->check(CLI::IsMember({"run", "maps", "both"}));
  cmd->add_flag("--maps-only", args->maps_only, "the same as --pairs-from maps");
  add_job_options(cmd, job, true);
  cmd->callback([args, job] {
    JobOptions options = job_options(*job);
    if (args->pairs_from)
      options.align.pairs_from = parse_pair_source(*args->pairs_from);
    if (args->maps_only)
      options.align.pairs_from = PairSource::maps;
    run_align(args->dataset, args->out, options);
  });
}

}  // namespace floorgrid::app
