#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/pipeline/align.hpp"

namespace floorgrid::io {

/// Wall-clock seconds of the main job's stages (metrics.json `timings_s`); the localization's
/// own stages come from the Alignment.
struct AlignmentTimings {
  double load = 0.0;       ///< reading the dataset
  double write = 0.0;      ///< writing the outputs (all but metrics.json itself and the heat maps)
  double heat_maps = 0.0;  ///< computing and writing heatmaps/ (every model's)
  /// The process's peak resident memory (MiB) after loading, and after writing every file but
  /// metrics.json (metrics.json `peak_memory_mib`, with the Alignment's stages).
  double load_peak_mib = 0.0;
  double write_peak_mib = 0.0;
};

/// One model's part of metrics.json (`models.<name>`): its failure, or its errors against the
/// truth, histogram, calibration, fit, cross-validation, uncertainty, back-and-forth and wall
/// distances. Shared by `align` and `evaluate`.
nlohmann::json model_metrics_json(const ModelAlignment& model);

/// Where models were judged (metrics.json `domain`): its kind, points and the truth's plan scale
/// there. Shared by `align` and `evaluate`.
nlohmann::json domain_json(const EvaluationDomain& domain);

/// Draws the plan's walls, mapped into the gridmap's frame by `plan_to_grid`, on a picture of the
/// gridmap's pixels: a DXF plan's segments and arcs as lines, else its wall samples as dots.
void draw_plan_walls(RgbImage& picture, const AlignmentInputs& inputs,
                     const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
                     const Colour& colour);

/// The overlay of a model (thesis Fig. 6.1-6.13): the plan's walls through the model (red) and
/// through the truth when known (green) on `background` (grid_picture of the gridmap).
RgbImage overlay_picture(const RgbImage& background, const AlignmentInputs& inputs,
                         const PointMapping& model, const std::optional<GroundTruth>& truth);

/// metrics.json (SPEC, a contract): pairs, plan scale, domain, per model errors against the
/// truth, fit time, cross-validated error, back-and-forth drift and wall distances, timings;
/// `floorplan_units` (a DXF plan's units and how they were decided) when not null.
nlohmann::json metrics_json(const Alignment& alignment, const std::string& dataset,
                            const AlignmentTimings& timings,
                            const nlohmann::json& floorplan_units = nullptr);

/// What write_alignment wrote.
struct AlignmentFiles {
  std::filesystem::path folder;              ///< the output folder
  std::vector<std::filesystem::path> files;  ///< every file, relative to the folder
  nlohmann::json metrics;                    ///< metrics.json as written
};

/// Writes the main job's results into `folder` (created when missing), each file atomically:
/// pairs.csv, model-<name>.json per fitted model, model.json (the model `auto` chose),
/// overlays/overlay-<name>.png (the plan's walls through each model, red, and through the truth
/// when known, green, on the gridmap), overlays/pairs.png (the pairs' gridmap endpoints, blue, on
/// the gridmap), heatmaps/heat-<name>.png and heatmaps/std-<name>.png (write_model_heat_maps)
/// and metrics.json last (with `dataset_path`, the manifest's absolute path, when given: what
/// `serve` shows the folder's model on). `timings.write` is filled in.
AlignmentFiles write_alignment(const Alignment& alignment, const AlignmentInputs& inputs,
                               const std::string& dataset, const std::filesystem::path& folder,
                               AlignmentTimings& timings,
                               const nlohmann::json& floorplan_units = nullptr,
                               const std::filesystem::path& dataset_path = {});

}  // namespace floorgrid::io
