#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "floorgrid/evaluation/zone_mask.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::app {

/// The plan layers' options of `floorgrid export` (SPEC revision 3, "Plan layers to the robot").
struct PlanLayersExportArgs {
  std::string zones;      ///< --zones FILE (GeoJSON in plan metres, or DXF with --layer)
  std::string waypoints;  ///< --waypoints FILE (GeoJSON points or CSV name,x,y,theta)
  std::string layer;      ///< --layer GLOB: the DXF layer holding the zones
  double margin_sigma = ZoneMaskOptions{}.margin_sigma;  ///< --margin-sigma K
  std::optional<double> speed_percent;  ///< --speed-percent: speed of zones without their own
};

/// Whether `format` is one of the plan layers' formats (nav2-keepout, nav2-speed,
/// nav2-waypoints, geojson).
bool is_plan_layers_format(const std::string& format);

/// Help text of the plan layers' formats, for `export --help`.
extern const char* const kPlanLayersHelp;

/// Runs one of the plan layers' formats: reads the zones and waypoints, maps them through
/// `model` onto the dataset's gridmap (needed by the masks), writes `out` (and the files beside
/// it) atomically and prints what it did. InputError on bad input.
void export_plan_layers(const std::string& format, const PlanLayersExportArgs& args,
                        const PointMapping& model, const std::optional<io::LoadedDataset>& dataset,
                        const std::optional<GridGeometry>& gridmap,
                        const std::filesystem::path& out);

}  // namespace floorgrid::app
