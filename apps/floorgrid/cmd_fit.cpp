// `floorgrid fit --pairs P.csv --model NAME [--cv K] [--unit U] --out FILE`: fit a mapping model.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/io/model_io.hpp"
#include "floorgrid/io/pairs_csv.hpp"
#include "floorgrid/io/value_json.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid::app {

void add_fit_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("fit", "Fit a mapping model to reference pairs");
  struct Args {
    std::string pairs, out;
    int cv = 0;
    double unit = 1.0;
    MappingOptions options;
  };
  auto args = std::make_shared<Args>();
  std::string models;
  for (const auto& n : mapping_model_names())
    models += (models.empty() ? "" : ", ") + n;
  cmd->add_option("--pairs", args->pairs, "pairs CSV: plan_x,plan_y,grid_x,grid_y[,weight]")
      ->required();
  cmd->add_option("--model", args->options.model, "model: " + models)->capture_default_str();
  cmd->add_option("--out", args->out, "model file to write (JSON)")->required();
  cmd->add_option("--cv", args->cv, "also report the k-fold cross-validated error (0: no)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--unit", args->unit,
                  "metres per unit of the pairs (the Halmstad pixel pairs: 0.05); the model "
                  "records it and `map` then reads and writes in those units")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--budget", args->options.common.reduction.budget,
                  "pairs kept by spatial binning in gp, gpgt, tps and dt")
      ->capture_default_str();
  cmd->add_option("--seed", args->options.common.seed, "seed of RANSAC and subsampling")
      ->capture_default_str();
  cmd->add_option("--inlier-threshold", args->options.ransac.inlier_threshold,
                  "metres: RANSAC inlier distance of the gt models")
      ->capture_default_str();
  cmd->add_option("--extrapolation", args->options.common.extrapolation_distance,
                  "metres from the nearest pair beyond which `map` flags a point extrapolated")
      ->capture_default_str();
  cmd->callback([args] {
    if (args->cv == 1)
      throw InputError("must be 0 or at least 2", {}, 0, "--cv");
    ReferencePairs pairs = io::read_pairs_csv(args->pairs, args->unit);
    io::prepare_output_folder(std::filesystem::path(args->out).parent_path().empty()
                                  ? std::filesystem::path(".")
                                  : std::filesystem::path(args->out).parent_path());
    auto model = make_mapping(args->options);
    model->set_unit(args->unit);
    const FitSummary s = model->fit(pairs);
    for (const auto& w : s.warnings)
      spdlog::warn("{}", w);
    if (args->cv >= 2) {
      CrossValidationOptions cv;
      cv.folds = args->cv;
      const CrossValidationResult r = cross_validate(args->options, pairs, cv);
      model->set_cv_error(r.mean_error_m);
    }
    io::write_model(*model, args->out);
    const FitSummary& f = model->summary();
    fmt::print("model     {}\n", f.model);
    fmt::print("pairs     {} given, {} duplicates merged ({} conflicting), {} used\n",
               f.pairs_given, f.pairs_merged, f.pairs_conflicting, f.pairs_used);
    if (f.reduction.applied) {
      fmt::print("reduction {} -> {} pairs by {:.3f} m cells\n", f.reduction.pairs_before,
                 f.reduction.pairs_after, f.reduction.cell_size);
    } else {
      fmt::print("reduction none\n");
    }
    if (f.inliers)
      fmt::print("inliers   {} of {}\n", *f.inliers, f.pairs_used);
    fmt::print("rms       {:.4f} m ({:.4g} units)\n", f.rms_m, f.rms_m / args->unit);
    if (f.details.size() > 0)
      fmt::print("details   {}\n", io::dump_json(f.details, -1));
    fmt::print("time      {:.3f} s\n", f.seconds);
    if (f.cv_error_m) {
      fmt::print("cv error  {:.4f} m ({:.4g} units, {}-fold)\n", *f.cv_error_m,
                 *f.cv_error_m / args->unit,
                 args->cv >= 2 ? args->cv : args->options.auto_select.cv.folds);
    }
    fmt::print("wrote     {}\n", args->out);
  });
}

}  // namespace floorgrid::app
