#include "floorgrid/io/export_inputs.hpp"

#include "floorgrid/io/map_io.hpp"

namespace floorgrid::io {

ExportMaps export_maps(const LoadedDataset& d) {
  const DatasetManifest& m = d.manifest;
  ExportMaps maps;
  LoadedMap grid = read_map(m.gridmap, m.gridmap_resolution, m.gridmap_origin, "gridmap");
  maps.gridmap = MapRaster{grid.image_path, grid.grid.geometry()};
  if (d.plan) {
    maps.plan_vector = *d.plan;
  } else {
    LoadedMap plan = read_map(m.floorplan, m.floorplan_resolution, m.floorplan_origin, "floorplan");
    maps.plan_raster = MapRaster{plan.image_path, plan.grid.geometry()};
    maps.plan_grid = std::move(plan.grid);
  }
  return maps;
}

}  // namespace floorgrid::io
