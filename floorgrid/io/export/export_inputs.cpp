#include "floorgrid/io/export/export_inputs.hpp"

namespace floorgrid::io {

ExportMaps export_maps(const LoadedDataset& d) {
  ExportMaps maps;
  maps.gridmap = d.gridmap_raster;
  if (d.plan) {
    maps.plan_vector = *d.plan;
  } else {
    maps.plan_raster = d.plan_raster;
    maps.plan_grid = d.plan_grid;  // cropping keeps every wall: only unknown border goes
  }
  return maps;
}

}  // namespace floorgrid::io
