#pragma once

#include <filesystem>

#include "floorgrid/io/dataset_loader.hpp"
#include "floorgrid/io/export_raster.hpp"

namespace floorgrid::io {

/// The maps of a loaded dataset as the exports need them: the gridmap and a raster plan read
/// again from their files, uncropped (the exports refer to the files' own pixels), and a DXF
/// plan's geometry as loading converted it (the units the model's plan metres are in).
ExportMaps export_maps(const LoadedDataset& dataset);

}  // namespace floorgrid::io
