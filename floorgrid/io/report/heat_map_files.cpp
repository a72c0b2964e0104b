#include "floorgrid/io/report/heat_map_files.hpp"

#include <chrono>
#include <cmath>

#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/report/heat_map_png.hpp"

namespace floorgrid::io {

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

/// One map written, and what metrics.json says of it.
json write_map(const std::filesystem::path& folder, const std::filesystem::path& file,
               const HeatMap& map, const OccupancyGrid& plan_grid) {
  const double clip = write_heat_map_png(folder / file, map, {}, &plan_grid);
  return {{"file", file.generic_string()}, {"quantity", map.quantity},
          {"cells", map.known()},          {"p95_m", number(map.quantile(0.95))},
          {"clip_m", number(clip)},        {"seconds", number(map.seconds)}};
}

}  // namespace

HeatMapDomain heat_map_domain(const AlignmentInputs& in, const std::optional<GroundTruth>& truth,
                              const std::string& kind, const HeatMapOptions& options) {
  const auto start = Clock::now();
  HeatMapDomain domain;
  domain.kind = kind;
  const GridGeometry& raster = in.plan_grid.geometry();
  if (truth && kind == "warp")
    domain.cells = observed_cells(raster, in.gridmap, batch_of(*truth), options);
  else if (truth && kind == "manual_pairs_hull" && in.manual_pairs)
    domain.cells = hull_cells(raster, in.manual_pairs->points_in_plan);
  domain.seconds = seconds_since(start);
  return domain;
}

ModelHeatMapValues model_heat_maps(const PointMapping& model, const AlignmentInputs& in,
                                   const std::optional<GroundTruth>& truth,
                                   const HeatMapDomain& domain, const HeatMapOptions& options) {
  ModelHeatMapValues out;
  const GridGeometry& raster = in.plan_grid.geometry();
  if (truth && !domain.cells.empty())
    out.error = error_heat_map(model, batch_of(*truth), raster, domain.cells, options);
  // Without a truth: where the model puts the plan on what the robot saw.
  const CellMask cells = !domain.cells.empty()
                             ? domain.cells
                             : observed_cells(
                                   raster, in.gridmap,
                                   [&model](const Eigen::Ref<const Eigen::Matrix2Xd>& points) {
                                     return model.forward_batch(points);
                                   },
                                   options);
  out.uncertainty = uncertainty_map(model, raster, cells, options);
  out.domain = domain.cells.empty() ? "model_observed" : domain.kind;
  return out;
}

ModelHeatMaps write_model_heat_maps(const std::filesystem::path& folder, const std::string& name,
                                    const PointMapping& model, const AlignmentInputs& in,
                                    const std::optional<GroundTruth>& truth,
                                    const HeatMapDomain& domain, const HeatMapOptions& options) {
  const auto start = Clock::now();
  prepare_output_folder(folder / "heatmaps");
  ModelHeatMaps out;
  out.metrics = json::object();
  const ModelHeatMapValues maps = model_heat_maps(model, in, truth, domain, options);
  if (maps.error) {
    const std::filesystem::path file =
        std::filesystem::path("heatmaps") / ("heat-" + name + ".png");
    out.metrics["error"] = write_map(folder, file, *maps.error, in.plan_grid);
    out.files.push_back(file);
  }
  const std::filesystem::path file = std::filesystem::path("heatmaps") / ("std-" + name + ".png");
  out.metrics["uncertainty"] = write_map(folder, file, maps.uncertainty, in.plan_grid);
  out.files.push_back(file);
  out.metrics["domain"] = maps.domain;
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace floorgrid::io
