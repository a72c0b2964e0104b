#include "floorgrid/io/plans/plan_drawing.hpp"

#include <algorithm>
#include <cctype>

#include "floorgrid/core/error.hpp"
#include "floorgrid/maps/layer_filter.hpp"

namespace floorgrid::io {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

PlanDrawingFile read_plan_drawing(const std::filesystem::path& path,
                                  std::optional<double> resolution, std::optional<Pose2> origin) {
  PlanDrawingFile f;
  f.path = path;
  if (!std::filesystem::exists(path))
    throw InputError("no such file", path.string(), 0, "--from-plan");
  const std::string ext = lower_extension(path);
  const bool bare = ext == ".png" || ext == ".pgm";
  if (!bare && (resolution || origin)) {
    throw InputError(
        "only a bare PNG/PGM image takes a resolution and an origin (a map YAML "
        "and a DXF say their own)",
        path.string(), 0, resolution ? "--resolution" : "--origin");
  }
  if (ext == ".dxf") {
    f.kind = "dxf";
    DxfFloorplan all = read_dxf(path);
    bool has_walls = false;
    for (const auto& [layer, types] : all.report.entities_by_layer) {
      has_walls = has_walls ||
                  std::any_of(kWallLayers.begin(), kWallLayers.end(),
                              [&](const std::string& glob) { return layer_matches(glob, layer); });
    }
    if (has_walls) {
      // Read again as a dataset naming these layers will be: the units decided on them.
      f.layers = kWallLayers;
      DxfReadOptions options;
      options.include_layers = kWallLayers;
      all = read_dxf(path, options);
    }
    f.drawing.vector = std::move(all.plan);
    f.warnings = all.report.warnings;
    f.dxf = std::move(all.report);
    return f;
  }
  if (!bare && ext != ".yaml" && ext != ".yml") {
    throw InputError(
        "not a drawing floorgrid reads: expected a map YAML, a PNG or PGM image "
        "(with --resolution), or a DXF",
        path.string(), 0, "--from-plan");
  }
  if (bare && !resolution) {
    throw InputError(
        "a bare image needs --resolution (metres per pixel; --origin x,y,yaw is "
        "optional)",
        path.string(), 0, "--resolution");
  }
  f.kind = "raster";
  LoadedMap map = read_map(path, resolution, origin, "plan");
  f.metadata = map.metadata;
  f.image = map.image_path;
  f.image_description = map.image_description;
  f.warnings = map.warnings;
  f.drawing.raster = std::move(map.grid);
  return f;
}

}  // namespace floorgrid::io
