#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/simulation/plan_dataset.hpp"

namespace floorgrid::io {

/// The layers a DXF drawing's walls are taken from when it has any: wall layers by their
/// usual names (`A-WALL`, `wall high`, `S-STEM-WALL`, ...).
inline const std::vector<std::string> kWallLayers = {"*WALL*"};

/// A drawing read for `simulate --from-plan`, and where it came from.
struct PlanDrawingFile {
  PlanDrawing drawing;                ///< the raster as read, or the DXF's walls (metres)
  std::filesystem::path path;         ///< the file given
  std::string kind;                   ///< "raster" or "dxf"
  MapMetadata metadata;               ///< a raster's map YAML fields (or the bare image's settings)
  std::filesystem::path image;        ///< a raster's image file
  std::string image_description;      ///< e.g. "PNG 8-bit grey with alpha"
  std::vector<std::string> layers;    ///< a DXF's include globs used (empty: every layer)
  std::optional<DxfReport> dxf;       ///< how a DXF was read
  std::vector<std::string> warnings;  ///< from the readers
};

/// Reads a drawing: a map YAML, a bare PNG/PGM image (`resolution` required, `origin`
/// optional, as `info` takes them), or a DXF (units decided by the reader; only its wall
/// layers, kWallLayers, when it has any). InputError naming the file or the option
/// (`--resolution`, `--origin`) otherwise.
PlanDrawingFile read_plan_drawing(const std::filesystem::path& path,
                                  std::optional<double> resolution, std::optional<Pose2> origin);

}  // namespace floorgrid::io
