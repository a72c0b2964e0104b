#include "floorgrid/io/jobs/alignment_writer.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>

#include "floorgrid/core/memory_usage.hpp"
#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/scans_csv.hpp"
#include "floorgrid/io/report/heat_map_files.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

/// A number, or null when it is not finite (JSON has no infinity).
json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

}  // namespace

json domain_json(const EvaluationDomain& d) {
  json j = {{"kind", d.kind}, {"points", d.points_in_plan.cols()}};
  if (d.truth_plan_scale)
    j["truth_plan_scale"] = number(*d.truth_plan_scale);
  return j;
}

json model_metrics_json(const ModelAlignment& m) {
  const ModelReport& r = m.report;
  json j = json::object();
  if (!r.failure.empty()) {
    j["failure"] = r.failure;
    return j;
  }
  if (r.errors) {
    j["mean_error_m"] = number(r.errors->mean);
    j["median_error_m"] = number(r.errors->median);
    j["p95_error_m"] = number(r.errors->p95);
    j["max_error_m"] = number(r.errors->max);
    j["error_histogram"] = r.histogram;
  }
  if (r.ideal_errors) {
    // Extension: the model fitted on ideal pairs (the truth at the pairs' plan points).
    j["ideal"] = {{"mean_error_m", number(r.ideal_errors->mean)},
                  {"median_error_m", number(r.ideal_errors->median)},
                  {"p95_error_m", number(r.ideal_errors->p95)}};
  }
  if (r.calibration) {
    // Extension: how often the true error lies within std_m and 2 std_m (ErrorModel).
    j["calibration"] = {{"within_1sigma", number(r.calibration->within_1sigma)},
                        {"within_2sigma", number(r.calibration->within_2sigma)},
                        {"median_std_m", number(r.calibration->median_std_m)},
                        {"points", r.calibration->points}};
  }
  j["fit_seconds"] = number(r.summary.seconds);
  j["cv_error_m"] = r.summary.cv_error_m ? number(*r.summary.cv_error_m) : json(nullptr);
  // Which cross-validation cv_error_m is: blocked (away from the pairs) or random.
  const std::optional<CrossValidationRecord>& cv = r.summary.cv;
  j["cv_kind"] = cv ? json(cv->kind) : json(nullptr);
  j["cv_folds"] = cv ? json(cv->folds) : json(nullptr);
  j["cv_block_m"] = cv && cv->kind == "blocked" ? number(cv->block_size) : json(nullptr);
  if (const std::optional<ErrorModel>& u = r.model->error_model()) {
    // Extension: the model's std_m = sqrt(base_std_m^2 + (growth d)^2 + shared_std_m^2), d from
    // the nearest pair.
    j["uncertainty"] = {{"base_std_m", number(u->base_std_m)},
                        {"growth", number(u->growth)},
                        {"shared_std_m", number(u->shared_std_m)},
                        {"residuals", u->residuals}};
  }
  j["rms_m"] = number(r.summary.rms_m);
  j["pairs_used"] = r.summary.pairs_used;
  if (r.summary.inliers)
    j["inliers"] = *r.summary.inliers;
  j["back_and_forth"] = {{"min_m", number(r.back_and_forth.min_m)},
                         {"mean_m", number(r.back_and_forth.mean_m)},
                         {"max_m", number(r.back_and_forth.max_m)},
                         {"points", r.back_and_forth.points},
                         {"not_invertible", r.back_and_forth.not_invertible}};
  j["wall_distance_median_m"] = number(m.wall_distance.median_m);
  j["wall_distance_near_pairs_median_m"] = number(m.wall_distance.near_median_m);
  j["wall_points_near_pairs"] = m.wall_distance.near_points;
  return j;
}

void draw_plan_walls(RgbImage& picture, const AlignmentInputs& in,
                     const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
                     const Colour& colour) {
  if (in.plan) {
    draw_plan(picture, in.gridmap.geometry(), *in.plan, plan_to_grid, colour);
    return;
  }
  Eigen::Matrix2Xd mapped(2, in.plan_wall_samples.cols());
  for (Eigen::Index i = 0; i < mapped.cols(); ++i)
    mapped.col(i) = plan_to_grid(in.plan_wall_samples.col(i));
  draw_points(picture, in.gridmap.geometry(), mapped, colour, 0);
}

RgbImage overlay_picture(const RgbImage& background, const AlignmentInputs& in,
                         const PointMapping& model, const std::optional<GroundTruth>& truth) {
  RgbImage picture = background;
  if (truth)
    draw_plan_walls(picture, in, *truth, {0, 170, 0});
  draw_plan_walls(picture, in, [&](const Eigen::Vector2d& p) { return model.forward(p); },
                  {220, 0, 0});
  return picture;
}

json metrics_json(const Alignment& a, const std::string& dataset, const AlignmentTimings& t,
                  const json& floorplan_units) {
  const DualLocalization& l = a.localization;
  json j;
  j["format"] = "floorgrid-metrics";
  j["version"] = 1;
  j["dataset"] = dataset;
  json pairs;
  pairs["count"] = l.pairs.size();
  pairs["rejected"] = json::object();
  for (const auto& [reason, count] : l.rejections.by_reason())
    pairs["rejected"][reason] = count;
  pairs["converged_fraction"] = number(l.converged_fraction);
  pairs["converged_periods"] = l.converged_periods.size();
  pairs["scans"] = l.scans.size();
  pairs["error_median_m"] = a.pair_errors ? number(a.pair_errors->median) : json(nullptr);
  if (a.pair_errors) {
    pairs["error_mean_m"] = number(a.pair_errors->mean);
    pairs["error_p95_m"] = number(a.pair_errors->p95);
  }
  // The pairs' own noise, from pairs of different visits to one place (no truth needed).
  pairs["noise_rms_m"] =
      a.pair_noise ? number(std::sqrt(a.pair_noise->mean_square_m2)) : json(nullptr);
  pairs["noise_differences"] = a.pair_noise ? a.pair_noise->differences : 0;
  // How far the plan's poses stood ahead of the gridmap's along the robot's heading, from
  // revisits; `applied`: taken out of the pairs.
  if (const auto& pull = l.pose_pull) {
    pairs["pose_pull"] = {{"along_m", number(pull->along_m)},
                          {"std_m", number(pull->std_m)},
                          {"scans", pull->scans},
                          {"comparisons", pull->comparisons},
                          {"applied", pull->applied}};
  } else {
    pairs["pose_pull"] = nullptr;
  }
  // The pairs above are the ones the models were fitted on: slid along their walls, when
  // they were; the filters' own are in pairs-localized.csv.
  if (a.wall_slide) {
    const auto& noise = a.wall_slide->noise;
    json slide = {{"applied", a.wall_slide->applied()},
                  {"iterations", a.wall_slide->iterations},
                  {"pairs_on_walls", a.wall_slide->pairs_on_walls},
                  {"noise_along_m", noise ? number(std::sqrt(noise->along_m2)) : json(nullptr)},
                  {"noise_across_m", noise ? number(std::sqrt(noise->across_m2)) : json(nullptr)},
                  {"median_slide_m", number(a.wall_slide->median_slide_m)},
                  {"p95_slide_m", number(a.wall_slide->p95_slide_m)}};
    if (a.localized_pair_errors) {
      slide["localized_error_median_m"] = number(a.localized_pair_errors->median);
      slide["localized_error_mean_m"] = number(a.localized_pair_errors->mean);
    }
    pairs["wall_slide"] = slide;
  }
  pairs["source"] = to_string(a.pairs_from);
  // Why the run's pairs were not used (the maps' stood in), or null.
  pairs["fallback"] =
      a.sources && !a.sources->fallback.empty() ? json(a.sources->fallback) : json(nullptr);
  j["pairs"] = pairs;
  // The bias every pair shares, in every model's std_m (PairSourceOptions::shared_bias).
  j["shared_bias"] = {{"std_m", number(a.shared_bias.std_m)},
                      {"from", a.shared_bias.from},
                      {"sources_m", number(a.shared_bias.sources_m)},
                      {"faces_m", number(a.shared_bias.faces_m)}};
  if (a.sources) {
    // The run's pairs judged on their own and against the maps' alignment (SPEC revision 3).
    const PairSourceCheck& c = *a.sources;
    j["sources"] = {
        {"chosen", c.chosen},
        {"filled_pairs", c.fill.size()},
        {"run",
         {{"accepted", c.run_accepted},
          {"localized", c.run_localized},
          {"failure", c.run_failure.empty() ? json(nullptr) : json(c.run_failure)},
          {"plan_match", c.run_match.judged ? number(c.run_match.score.score) : json(nullptr)},
          {"coverage", number(c.coverage)},
          {"pair_scans", c.pair_scans},
          {"scans", c.scans}}},
        {"maps",
         {{"accepted", c.maps_accepted},
          {"plan_match", c.maps_match.judged ? number(c.maps_match.score.score) : json(nullptr)},
          {"failure", c.maps_failure.empty() ? json(nullptr) : json(c.maps_failure)}}},
        {"agreement",
         c.compared ? json{{"agree", c.agree},
                           {"median_m", number(c.disagreement_median_m)},
                           {"p90_m", number(c.disagreement_p90_m)},
                           {"local_median_m", number(c.disagreement_local_median_m)},
                           {"tolerance_m", number(c.disagreement_tolerance_m)},
                           {"run_scale", number(c.run_scale)},
                           {"maps_scale", number(c.maps_scale)},
                           {"run_scale_at_drawn_walls", c.run_scale_at_drawn_walls > 0.0
                                                            ? number(c.run_scale_at_drawn_walls)
                                                            : json(nullptr)},
                           {"scale_tolerance", number(c.scale_tolerance)}}
                    : json(nullptr)}};
  }
  if (a.maps) {
    const MapAlignment& m = *a.maps;
    const ScoredSimilarity& r = m.registration.best;
    j["maps_only"] = {
        {"accepted", m.accepted},
        {"fitness", number(m.fit.score)},
        {"min_fitness", number(m.options.min_fitness)},
        {"min_on_walls", number(m.options.min_on_walls)},
        {"ambiguity", number(m.ambiguity)},
        {"max_ambiguity", number(m.options.max_ambiguity)},
        {"on_walls", number(m.fit.on_walls)},
        {"in_free_space", number(m.fit.in_free_space)},
        {"pairs", m.pairs.size()},
        {"points", m.points},
        {"stages", m.stages},
        {"median_distance_m", number(m.median_distance_m)},
        {"warp_scale", number(m.scale.scale)},
        {"warp_scale_relative_std", number(m.scale.relative_std)},
        {"diagnosis", m.diagnosis},
        {"seconds", number(m.seconds)},
        {"registration",
         {{"scale", number(r.transform.scale)},
          {"theta_deg", number(r.transform.theta * 180.0 / std::numbers::pi)},
          {"score", number(r.score)},
          {"on_walls", number(r.on_walls)},
          {"in_free_space", number(r.in_free_space)},
          {"runner_up_score", number(m.registration.runner_up().score)},
          {"correlation", m.registration.correlation},
          {"seconds", number(m.registration.seconds)}}},
        {"faces",
         {{"fitted", m.faces.fitted},
          {"exterior_offset_m", number(m.faces.exterior_offset / r.transform.scale)},
          {"partition_offset_m", number(m.faces.partition_offset / r.transform.scale)},
          {"exterior_points", m.faces.exterior_points},
          {"partition_points", m.faces.partition_points},
          {"note", m.faces.note}}}};
    if (m.runner_up) {
      j["maps_only"]["runner_up"] = {
          {"fitness", number(m.runner_up->fit.score)},
          {"on_walls", number(m.runner_up->fit.on_walls)},
          {"in_free_space", number(m.runner_up->fit.in_free_space)},
          {"scale", number(m.runner_up->start.scale)},
          {"theta_deg", number(m.runner_up->start.theta * 180.0 / std::numbers::pi)}};
    }
  }
  j["plan_scale"] = number(l.plan_scale);
  j["plan_scale_std"] = number(l.plan_scale_std);
  j["plan_scale_estimated"] = l.plan_scale_estimated;
  // How far the plan walls' faces lay in front of where the matchers met them (world metres),
  // fitted with the scale.
  j["plan_surface_shift_m"] = number(l.plan_surface_shift);
  j["plan_surface_shift_std_m"] = number(l.plan_surface_shift_std);
  j["plan_surface_shift_used"] = l.plan_scale_at_drawn_walls > 0.0;
  if (!floorplan_units.is_null())
    j["floorplan_units"] = floorplan_units;
  j["localization"] = {{"grid_start_scan", l.grid_start_scan},
                       {"longest_gap_scans", l.longest_gap},
                       {"plan_start_scan", l.plan_start_scan},
                       {"start_plan", {l.start.plan.x, l.start.plan.y, l.start.plan.theta}},
                       {"start_grid", {l.start.grid.x, l.start.grid.y, l.start.grid.theta}},
                       {"plan_divergences", l.plan_divergences.by_reason},
                       {"grid_divergences", l.grid_divergences.by_reason},
                       {"grid_restarts",
                        {{"near", l.grid_restarts.near},
                         {"near_failed", l.grid_restarts.near_failed},
                         {"global", l.grid_restarts.global},
                         {"from_plan", l.grid_restarts.from_plan},
                         {"mended_scans", l.grid_restarts.mended_scans}}},
                       {"notes", l.notes}};
  if (a.plan_match.judged) {
    const ScoredSimilarity& m = a.plan_match.score;
    j["plan_match"] = {{"score", number(m.score)},
                       {"on_walls", number(m.on_walls)},
                       {"in_free_space", number(m.in_free_space)},
                       {"plan_scale", number(1.0 / m.transform.scale)}};
  }
  j["domain"] = domain_json(a.domain);
  j["models"] = json::object();
  for (const ModelAlignment& m : a.models)
    j["models"][m.report.name] = model_metrics_json(m);
  j["chosen_model"] = a.chosen.empty() ? json(nullptr) : json(a.chosen);
  j["timings_s"] = {{"load", t.load},
                    {"global_localization", l.global_localization_seconds},
                    {"scale_search", l.scale_search_seconds},
                    {"localize", l.localize_seconds},
                    {"pairs", l.pairs_seconds},
                    {"maps_alignment", a.maps ? a.maps->seconds : 0.0},
                    {"wall_slide", a.wall_slide_seconds},
                    {"fit", a.fit_seconds},
                    {"evaluate", a.evaluate_seconds},
                    {"write", t.write},
                    {"heat_maps", t.heat_maps}};
  // Where the memory goes: the peak so far at the end of each stage that ran (it only grows).
  json peak = json::object();
  if (t.load_peak_mib > 0.0)
    peak["load"] = t.load_peak_mib;
  for (const auto& [stage, mib] : a.peak_memory_mib)
    peak[stage] = mib;
  if (t.write_peak_mib > 0.0)
    peak["write"] = t.write_peak_mib;
  j["peak_memory_mib"] = peak;
  return j;
}

AlignmentFiles write_alignment(const Alignment& a, const AlignmentInputs& in,
                               const std::string& dataset, const std::filesystem::path& folder,
                               AlignmentTimings& timings, const json& floorplan_units,
                               const std::filesystem::path& dataset_path) {
  const auto start = std::chrono::steady_clock::now();
  prepare_output_folder(folder);
  prepare_output_folder(folder / "overlays");
  AlignmentFiles files{folder, {}, {}};
  write_pairs_csv(a.localization.pairs, folder / "pairs.csv");
  files.files.emplace_back("pairs.csv");
  if (a.localized_pairs.size() > 0) {
    write_pairs_csv(a.localized_pairs, folder / "pairs-localized.csv");
    files.files.emplace_back("pairs-localized.csv");
  }
  write_scans_csv(a.localization, in.log, folder / "scans.csv");
  files.files.emplace_back("scans.csv");
  const RgbImage background = grid_picture(in.gridmap);
  {
    // Where the pairs are: their gridmap endpoints in blue on the gridmap (the report shows it).
    RgbImage picture = background;
    draw_points(picture, in.gridmap.geometry(), a.localization.pairs.points_in_grid, {30, 90, 220},
                0);
    const std::filesystem::path pairs_picture = std::filesystem::path("overlays") / "pairs.png";
    write_png_rgb(folder / pairs_picture, picture.width, picture.height, picture.rgb);
    files.files.push_back(pairs_picture);
  }
  const HeatMapDomain heat_domain = heat_map_domain(in, a.truth, a.domain.kind);
  timings.heat_maps = heat_domain.seconds;
  std::map<std::string, json> heat_maps;
  for (const ModelAlignment& m : a.models) {
    if (!m.report.model)
      continue;
    const PointMapping& model = *m.report.model;
    const std::string name = m.report.name;
    write_model(model, folder / ("model-" + name + ".json"));
    files.files.emplace_back("model-" + name + ".json");
    const RgbImage picture = overlay_picture(background, in, model, a.truth);
    const std::filesystem::path overlay =
        std::filesystem::path("overlays") / ("overlay-" + name + ".png");
    write_png_rgb(folder / overlay, picture.width, picture.height, picture.rgb);
    files.files.push_back(overlay);
    const ModelHeatMaps heat = write_model_heat_maps(folder, name, model, in, a.truth, heat_domain);
    files.files.insert(files.files.end(), heat.files.begin(), heat.files.end());
    heat_maps[name] = heat.metrics;
    timings.heat_maps += heat.seconds;
  }
  // auto's choice is also a model of its own: model.json is that model's file.
  if (!a.chosen.empty()) {
    for (const ModelAlignment& m : a.models) {
      if (m.report.name == "auto" && m.report.model) {
        if (const auto* chooser = dynamic_cast<const AutoMapping*>(m.report.model.get())) {
          write_model(chooser->chosen(), folder / "model.json");
          files.files.emplace_back("model.json");
        }
      }
    }
  }
  timings.write = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                  timings.heat_maps;
  timings.write_peak_mib = peak_resident_mib();
  json metrics = metrics_json(a, dataset, timings, floorplan_units);
  if (!dataset_path.empty())
    metrics["dataset_path"] = std::filesystem::absolute(dataset_path).lexically_normal().string();
  for (const auto& [name, heat] : heat_maps)
    metrics["models"][name]["heat_map"] = heat;
  write_file_atomically(folder / "metrics.json", metrics.dump(1) + "\n");
  files.files.emplace_back("metrics.json");
  files.metrics = std::move(metrics);
  return files;
}

}  // namespace floorgrid::io
