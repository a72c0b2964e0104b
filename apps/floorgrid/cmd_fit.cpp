// `floorgrid fit --pairs P.csv --model NAME [--cv K] [--unit U] --out FILE`: fit a mapping model.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <charconv>
#include <cmath>
#include <vector>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/system_memory.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/mapping/checked_fit.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid::app {

void add_fit_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("fit", "Fit a mapping model to reference pairs");
  struct Args {
    std::string pairs, out;
    int cv = 5;
    std::string cv_kind = to_string(CrossValidationOptions{}.kind);
    double unit = 1.0;
    MappingOptions options;
    // Signed, so that a negative budget is refused rather than wrapped around.
    long long budget = static_cast<long long>(MappingOptions{}.common.reduction.budget);
    double memory_limit_gb = io::default_memory_limit_gb();
    std::string inlier_threshold = "auto";
  };
  auto args = std::make_shared<Args>();
  std::string models;
  for (const ModelEntry& entry : model_registry())
    models += fmt::format("\n  {:<10} {}", entry.name, entry.traits.description);
  cmd->add_option("--pairs", args->pairs, "pairs CSV: plan_x,plan_y,grid_x,grid_y[,weight]")
      ->required();
  cmd->add_option("--model", args->options.model, "the model, one of:" + models)
      ->capture_default_str();
  cmd->add_option("--out", args->out, "model file to write (JSON)")->required();
  cmd->add_option("--cv", args->cv,
                  "k-fold cross-validated error, and the model's std_m: its shape from "
                  "blocked folds' held-out errors, its level from runs folds' less the pairs' "
                  "own noise (0: neither; std_m then empty)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--cv-kind", args->cv_kind,
                  "folds of whole spatial blocks (blocked: the error away from the pairs), of "
                  "pairs dealt at random (random), or of stretches of the pairs in their order "
                  "(runs: pairs from `pairs`, in scan order); also how auto compares its "
                  "candidates")
      ->check(CLI::IsMember({"blocked", "random", "runs"}))
      ->capture_default_str();
  cmd->add_option("--cv-block", args->options.auto_select.cv.block_size,
                  "metres, side of the blocks of blocked folds (0: chosen from the pairs)")
      ->capture_default_str();
  cmd->add_option("--unit", args->unit,
                  "metres per unit of the pairs (the Halmstad pixel pairs: 0.05); the model "
                  "records it and `map` then reads and writes in those units")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--budget", args->budget, "pairs kept by spatial binning in gp, gpgt, tps and dt")
      ->capture_default_str();
  cmd->add_option("--memory-limit", args->memory_limit_gb,
                  "GiB a fit may use at most (default: half of this machine's memory)")
      ->capture_default_str();
  cmd->add_option("--seed", args->options.common.seed, "seed of RANSAC and subsampling")
      ->check(seed_check())
      ->capture_default_str();
  cmd->add_option("--inlier-threshold", args->inlier_threshold,
                  fmt::format("metres: RANSAC inlier distance of the gt models, or "
                              "auto: {:g} times the pairs' noise scale, estimated from the fit",
                              RansacOptions{}.threshold_sigmas))
      ->capture_default_str();
  cmd->add_option("--extrapolation", args->options.common.extrapolation_distance,
                  "metres from the nearest pair beyond which `map` flags a point extrapolated")
      ->capture_default_str();
  cmd->add_option("--shared-std", args->options.uncertainty.shared_std,
                  "metres: a bias all the pairs share, which their cross-validation cannot see "
                  "(how far the drawing or the pairs may be off as a whole), added to std_m in "
                  "quadrature")
      ->capture_default_str();
  cmd->callback([args] {
    const double shared = args->options.uncertainty.shared_std;
    if (!(shared >= 0.0 && shared <= 1e3))
      throw InputError(fmt::format("must be in [0, 1000] metres (got {})", shared), {}, 0,
                       "--shared-std");
    if (args->cv == 1)
      throw InputError("must be 0 or at least 2", {}, 0, "--cv");
    if (args->budget < 3 || args->budget > 10'000'000)
      throw InputError(fmt::format("must be in [3, 10000000] (got {})", args->budget), {}, 0,
                       "--budget");
    if (!(args->memory_limit_gb > 0.0 && args->memory_limit_gb < 1e6))
      throw InputError("must be a positive number of GiB", {}, 0, "--memory-limit");
    CrossValidationOptions& cv = args->options.auto_select.cv;
    cv.kind = parse_cv_kind(args->cv_kind);
    if (!(cv.block_size >= 0.0 && cv.block_size <= kMaxCoordinate)) {
      throw InputError(fmt::format("must be 0 (chosen from the pairs) or a size in metres (got {})",
                                   cv.block_size),
                       {}, 0, "--cv-block");
    }
    const double extrapolation = args->options.common.extrapolation_distance;
    if (!(extrapolation >= 0.0 && extrapolation <= kMaxCoordinate))
      throw InputError(fmt::format("must be a distance in [0, 1e7] metres (got {})", extrapolation),
                       {}, 0, "--extrapolation");
    if (args->inlier_threshold != "auto") {
      const std::string& text = args->inlier_threshold;
      double threshold = 0.0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), threshold);
      if (error != std::errc() || end != text.data() + text.size() ||
          !(threshold > 0.0 && threshold <= kMaxCoordinate)) {
        throw InputError(
            fmt::format("must be auto or a distance in (0, 1e7] metres (got {})", text), {}, 0,
            "--inlier-threshold");
      }
      args->options.ransac.inlier_threshold = threshold;
    }
    args->options.common.reduction.budget = static_cast<std::size_t>(args->budget);
    refuse_overwriting_input(args->pairs, args->out, "--out");
    std::vector<long> lines;
    ReferencePairs pairs = io::read_pairs_csv(args->pairs, args->unit, &lines);
    const std::filesystem::path folder = std::filesystem::path(args->out).parent_path();
    const io::OutputFolder out_folder(folder.empty() ? std::filesystem::path(".") : folder);
    const CheckedFit fit = fit_checked(
        pairs, {args->options, args->cv, args->unit, args->memory_limit_gb}, args->pairs, lines);
    for (const auto& w : fit.summary.warnings)
      spdlog::warn("{}", w);
    const auto& model = fit.model;
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
    if (f.cv_error_m && f.cv) {
      const std::string blocks =
          f.cv->kind == "blocked" ? fmt::format(", {:.2f} m blocks", f.cv->block_size) : "";
      fmt::print("cv error  {:.4f} m ({:.4g} units, {}-fold {}{})\n", *f.cv_error_m,
                 *f.cv_error_m / args->unit, f.cv->folds, f.cv->kind, blocks);
    } else if (f.cv_error_m) {
      fmt::print("cv error  {:.4f} m ({:.4g} units, {}-fold)\n", *f.cv_error_m,
                 *f.cv_error_m / args->unit,
                 args->cv >= 2 ? args->cv : args->options.auto_select.cv.folds);
    }
    if (const std::optional<ErrorModel>& u = model->error_model()) {
      const std::string bias_term =
          u->shared_std_m > 0.0 ? fmt::format(" + {:.4f}^2", u->shared_std_m) : std::string();
      fmt::print(
          "std_m     sqrt({:.4f}^2 + ({:.4f} d)^2{}) m, d: metres from the nearest pair ({} "
          "held-out pairs){}\n",
          u->base_std_m, u->growth, bias_term, u->residuals,
          bias_term.empty() ? "" : "; the last term a bias all pairs share (--shared-std)");
    } else {
      fmt::print("std_m     none ({})\n", args->cv >= 2 && cv.kind == CrossValidationKind::blocked
                                              ? "too few held-out pairs"
                                              : "needs blocked cross-validation, --cv >= 2");
    }
    fmt::print("wrote     {}\n", args->out);
  });
}

}  // namespace floorgrid::app
