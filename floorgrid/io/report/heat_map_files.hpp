#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/evaluation/heat_map.hpp"
#include "floorgrid/pipeline/align.hpp"

namespace floorgrid::io {

/// The cells of the plan grid where a truth holds (the heat maps' domain, SPEC "Evaluation" in
/// cells): through a warp, the cells whose true grid position the gridmap observed; with manual
/// pairs, the cells inside their hull; none without a truth.
struct HeatMapDomain {
  std::string kind = "none";  ///< the truth's kind: "warp", "manual_pairs_hull" or "none"
  CellMask cells;             ///< one byte per plan grid cell; empty without a truth
  double seconds = 0.0;       ///< wall-clock time of finding them
};

/// The heat-map domain of a dataset's truth (`kind` as DatasetTruth::kind).
HeatMapDomain heat_map_domain(const AlignmentInputs& inputs,
                              const std::optional<GroundTruth>& truth, const std::string& kind,
                              const HeatMapOptions& options = {});

/// A model's heat maps over the plan grid: its error against the truth over the truth's cells
/// (with a truth), and its own uncertainty (std_m, or the distance to the nearest pair when it
/// states no std_m) over the truth's cells, or without a truth over the cells it maps onto what
/// the gridmap observed.
struct ModelHeatMapValues {
  std::optional<HeatMap> error;  ///< |model - truth|, with a truth
  HeatMap uncertainty;           ///< the model's own say
  std::string domain;            ///< the cells': the truth's kind, or "model_observed"
};

/// Computes a model's heat maps (`domain` from heat_map_domain).
ModelHeatMapValues model_heat_maps(const PointMapping& model, const AlignmentInputs& inputs,
                                   const std::optional<GroundTruth>& truth,
                                   const HeatMapDomain& domain, const HeatMapOptions& options = {});

/// What write_model_heat_maps wrote.
struct ModelHeatMaps {
  std::vector<std::filesystem::path> files;  ///< relative to the output folder
  nlohmann::json metrics;                    ///< metrics.json `models.<name>.heat_map`
  double seconds = 0.0;                      ///< computing and writing them
};

/// Writes a model's heat maps (model_heat_maps) into `folder`/heatmaps (created when missing):
/// heat-<name>.png, the error (with a truth), and std-<name>.png, the uncertainty. Each PNG
/// carries its colour bar (in metres, with the clip).
ModelHeatMaps write_model_heat_maps(const std::filesystem::path& folder, const std::string& name,
                                    const PointMapping& model, const AlignmentInputs& inputs,
                                    const std::optional<GroundTruth>& truth,
                                    const HeatMapDomain& domain,
                                    const HeatMapOptions& options = {});

}  // namespace floorgrid::io
