// `floorgrid align DATASET --out DIR`: pairs, every model fitted and judged, overlays, metrics.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/dataset_run.hpp"
#include "apps/floorgrid/job_options.hpp"
#include "apps/floorgrid/progress.hpp"
#include "apps/floorgrid/summaries.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/jobs/alignment_job.hpp"

namespace floorgrid::app {

void run_align(const std::string& dataset, const std::string& out, const JobOptions& options) {
  const io::OutputFolder out_folder(out);
  const auto job = io::load_alignment_job(dataset, options);
  report_loading(job->dataset);
  ProgressLine progress;
  const Alignment a = io::run_alignment_job(*job, options, [&](const AlignmentProgress& p) {
    progress.update(p.stage == "fit" ? "fit " + p.detail : p.detail, p.done, p.total);
  });
  progress.finish();
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
  const io::AlignmentFolder folder = io::write_alignment_folder(*job, a, options, out);
  fmt::print("\nwrote {} files to {} (metrics.json, model.json, overlays/)\n",
             folder.files.files.size(), folder.files.folder.string());
  if (folder.exports) {
    for (const std::string& skipped : folder.exports->skipped)
      spdlog::info("export skipped: {}", skipped);
    fmt::print(
        "exports     {} files in {} ({:.2f} s; `floorgrid export --help` says what "
        "each is)\n",
        folder.exports->files.size(), (std::filesystem::path(out) / "exports").string(),
        folder.exports_seconds);
  } else if (!folder.exports_error.empty()) {
    spdlog::warn("exports not written: {}", folder.exports_error);
  }
  if (folder.report) {
    fmt::print("report      {} ({:.2f} s; open it in a browser, it needs no network)\n",
               folder.report->string(), folder.report_seconds);
  } else {
    spdlog::warn("report.html not written: {}", folder.report_error);
  }
  if (!folder.failure.empty())
    throw AlignmentFailure(folder.failure);
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
