#pragma once

#include <filesystem>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/export/export_raster.hpp"

namespace floorgrid::io {

/// The maps of a loaded dataset as the exports need them: the gridmap's and a raster plan's
/// image files with their uncropped geometry, as loading recorded them (the exports refer to
/// the files' own pixels), a raster plan's cells, and a DXF plan's geometry as loading converted
/// it (the units the model's plan metres are in). Reads no file.
ExportMaps export_maps(const LoadedDataset& dataset);

}  // namespace floorgrid::io
