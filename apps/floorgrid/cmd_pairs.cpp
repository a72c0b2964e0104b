// `floorgrid pairs DATASET --out pairs.csv`: reference pairs by dual Monte Carlo localization.
#include <fmt/format.h>

#include <chrono>

#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/dataset_run.hpp"
#include "apps/floorgrid/job_options.hpp"
#include "apps/floorgrid/progress.hpp"
#include "apps/floorgrid/summaries.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/scans_csv.hpp"

namespace floorgrid::app {

void add_pairs_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("pairs", "Reference pairs by dual Monte Carlo localization");
  struct Args {
    std::string dataset, out, scans;
  };
  auto args = std::make_shared<Args>();
  auto job = std::make_shared<JobArgs>();
  cmd->add_option("DATASET", args->dataset, "dataset.yaml or its folder")->required();
  cmd->add_option("--out", args->out, "pairs CSV to write (plan_x,plan_y,grid_x,grid_y)")
      ->required();
  cmd->add_option("--scans", args->scans,
                  "CSV to write with each filter's pose, state and fit per scan (as align's "
                  "scans.csv)");
  add_job_options(cmd, job, false);
  cmd->callback([args, job] {
    const JobOptions options = job_options(*job);
    validate(options.align.wall_slide);
    const std::filesystem::path out(args->out);
    const io::OutputFolder out_folder(out.parent_path().empty() ? "." : out.parent_path());
    const io::LoadedDataset d =
        io::load_dataset(args->dataset, options.raster, options.limits, options.units);
    report_loading(d);
    ProgressLine progress;
    const DualLocalizerInputs inputs = dual_inputs(d);
    const DualLocalization l =
        localize_dual(inputs, options.align.localization, [&](const DualProgress& p) {
          progress.update(p.phase, p.scan, p.scans, p.converged ? "converged" : "not converged");
        });
    progress.finish();
    if (!args->scans.empty())
      io::write_scans_csv(l, *d.log, args->scans);
    require_localized(l.status, d);
    require_pairs(l, d);
    const PlanMatch match =
        judge_plan_match(inputs.gridmap, inputs.plan, plan_walls_of(inputs.plan_geometry), l.pairs,
                         options.align.localization.plan_location.map_registration);
    require_plan_match(match, d, options.align.localization.plan_location);
    const auto errors_of = [&](const ReferencePairs& pairs) -> std::optional<ErrorStatistics> {
      if (!d.truth_warp || pairs.size() == 0)
        return std::nullopt;
      return pair_errors(pairs, warp_truth(d));
    };
    // As align: the pairs slid along their walls, the ones its models are fitted on.
    std::optional<WallSlide> slide;
    if (options.align.wall_slide.iterations > 0)
      slide = slide_pairs_along_walls(l.pairs, inputs.gridmap, options.align.wall_slide,
                                      options.align.models.mapping);
    const ReferencePairs& pairs = slide ? slide->pairs : l.pairs;
    io::write_pairs_csv(pairs, out);
    print_localization(l, errors_of(pairs));
    if (slide)
      print_wall_slide(*slide, static_cast<std::size_t>(pairs.size()), errors_of(l.pairs));
    fmt::print("wrote       {}\n", out.string());
  });
}

}  // namespace floorgrid::app
