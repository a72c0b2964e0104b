// `floorgrid evaluate DATASET --model FILE --out DIR`: one model file judged on a dataset (thesis
// ch. 6): errors against the truth, histogram, heat maps, back-and-forth, overlay, metrics.json.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/dataset_run.hpp"
#include "apps/floorgrid/job_options.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/jobs/alignment_writer.hpp"
#include "floorgrid/io/report/heat_map_files.hpp"

namespace floorgrid::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

void run_evaluate(const std::string& dataset, const std::string& model_file, const std::string& out,
                  const JobOptions& options) {
  const io::OutputFolder out_folder(out);
  const auto load_start = Clock::now();
  const std::shared_ptr<PointMapping> model =
      io::read_model(model_file, options.align.models.mapping);
  const io::LoadedDataset d =
      io::load_dataset(dataset, options.raster, options.limits, options.units);
  report_loading(d);
  const double load_seconds = seconds_since(load_start);
  // evaluate needs no run: the maps and the truth are all it judges on.
  const AlignmentInputs inputs{d.plan_grid,
                               d.plan ? &*d.plan : nullptr,
                               d.plan_wall_samples,
                               d.gridmap,
                               dataset_log_or_none(d),
                               std::nullopt,
                               d.manifest.floorplan_scale,
                               warp_truth(d),
                               d.manual_pairs ? &*d.manual_pairs : nullptr};

  // The same truth, domain and judge as align's.
  const auto evaluate_start = Clock::now();
  const DatasetTruth truth = dataset_truth(inputs);
  const EvaluationDomain domain = truth_domain(inputs, truth, options.align.domain_spacing);
  ModelAlignment judged;
  judged.report.name = model->name();
  judged.report.summary = model->summary();
  judged.report.model = model;
  // Without a truth the drift is followed over all plan wall samples.
  judge_model(judged.report, domain, truth.plan_to_grid,
              truth.plan_to_grid ? domain.points_in_plan : d.plan_wall_samples,
              options.align.models);
  judged.wall_distance = wall_distance(
      d.plan_wall_samples, model->forward_batch(d.plan_wall_samples), d.gridmap,
      model->support().points_in_plan, options.align.near_pairs, options.align.wall_distance_cap);
  const double evaluate_seconds = seconds_since(evaluate_start);

  const auto write_start = Clock::now();
  const std::filesystem::path folder(out);
  io::prepare_output_folder(folder);
  io::prepare_output_folder(folder / "overlays");
  const std::string name = judged.report.name;
  const io::HeatMapDomain heat_domain = io::heat_map_domain(inputs, truth.plan_to_grid, truth.kind);
  const io::ModelHeatMaps heat =
      io::write_model_heat_maps(folder, name, *model, inputs, truth.plan_to_grid, heat_domain);
  const double heat_seconds = heat_domain.seconds + heat.seconds;
  const RgbImage overlay =
      io::overlay_picture(grid_picture(d.gridmap), inputs, *model, truth.plan_to_grid);
  const std::filesystem::path overlay_file =
      std::filesystem::path("overlays") / ("overlay-" + name + ".png");
  io::write_png_rgb(folder / overlay_file, overlay.width, overlay.height, overlay.rgb);

  nlohmann::json j;
  j["format"] = "floorgrid-metrics";
  j["version"] = 1;
  j["verb"] = "evaluate";
  j["dataset"] = d.manifest.display_name();
  j["model_file"] = model_file;
  j["truth"] = truth.kind;
  j["domain"] = io::domain_json(domain);
  nlohmann::json m = io::model_metrics_json(judged);
  m["heat_map"] = heat.metrics;
  j["models"] = {{name, m}};
  j["timings_s"] = {{"load", load_seconds},
                    {"evaluate", evaluate_seconds},
                    {"heat_maps", heat_seconds},
                    {"write", seconds_since(write_start) - heat_seconds}};
  io::write_file_atomically(folder / "metrics.json", j.dump(1) + "\n");

  const ModelReport& r = judged.report;
  fmt::print("model       {} from {}\n", name, model_file);
  if (r.errors) {
    fmt::print(
        "error       mean {:.3f} m, median {:.3f} m, p95 {:.3f} m over {} wall points ({})\n",
        r.errors->mean, r.errors->median, r.errors->p95, r.errors->count, domain.kind);
  }
  fmt::print(
      "drift       back-and-forth x{}: min {:.2e} m, mean {:.2e} m, max {:.2e} m over {} "
      "points ({} not invertible)\n",
      options.align.models.back_and_forth_rounds, r.back_and_forth.min_m, r.back_and_forth.mean_m,
      r.back_and_forth.max_m, r.back_and_forth.points, r.back_and_forth.not_invertible);
  std::string heat_files;
  for (const std::filesystem::path& file : heat.files)
    heat_files += (heat_files.empty() ? "" : ", ") + file.generic_string();
  fmt::print("heat maps   {} in {:.2f} s\n", heat_files, heat_seconds);
  fmt::print("wrote       metrics.json, {}, heatmaps/ to {}\n", overlay_file.string(), out);
  write_report(folder);
  if (!truth.plan_to_grid) {
    // The uncertainty map and the drift are written; the errors cannot be.
    throw InputError(
        "the dataset has no truth (truth.warp or truth.manual_pairs): errors against the truth "
        "not measured; wrote the uncertainty map and the back-and-forth",
        d.manifest.manifest_path.string(), 0, "truth");
  }
}

void add_evaluate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "evaluate",
      "Judge a model file on a dataset: errors against the truth, heat maps, back-and-forth");
  struct Args {
    std::string dataset, model, out;
  };
  auto args = std::make_shared<Args>();
  auto job = std::make_shared<JobArgs>();
  cmd->add_option("DATASET", args->dataset, "dataset.yaml or its folder")->required();
  cmd->add_option("--model", args->model, "model file (model.json or model-<name>.json)")
      ->required();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->required();
  add_job_options(cmd, job, false);
  cmd->callback(
      [args, job] { run_evaluate(args->dataset, args->model, args->out, job_options(*job)); });
}

}  // namespace floorgrid::app
