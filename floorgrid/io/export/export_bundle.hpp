#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/export/export_raster.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::io {

/// What write_exports wrote and left out.
struct ExportFiles {
  std::vector<std::filesystem::path> files;  ///< relative to the folder given
  std::vector<std::string> skipped;          ///< "format: why" for each export not written
};

/// Every export the inputs allow, for one model, into `folder` (created when missing), each
/// file atomically: plan.points (QGIS; from `pairs`), plan.vrt (GDAL; a raster plan only),
/// gridmap.vrt (GDAL, the gridmap into the plan frame), rmf-layer.yaml (traffic-editor),
/// plan-walls.yaml + .pgm (nav2). `pairs` in metres.
ExportFiles write_exports(const PointMapping& model, const ReferencePairs& pairs,
                          const ExportMaps& maps, const std::filesystem::path& folder);

}  // namespace floorgrid::io
