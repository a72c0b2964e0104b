#pragma once

#include <filesystem>
#include <string>

#include "floorgrid/evaluation/heat_map.hpp"
#include "floorgrid/io/report/bitmap_font.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid::io {

/// How a heat map becomes a picture.
struct HeatMapStyle {
  /// Metres at the top of the colour bar; larger values are drawn in its top colour. 0: the
  /// 95th percentile of the map's values rounded up to 1, 2, 2.5 or 5 times a power of ten.
  double clip_m = 0.0;
  double quantile = 0.95;     ///< the percentile of the automatic clip
  double min_clip_m = 0.001;  ///< metres: the automatic clip is at least this
  /// false: the map alone, one pixel per cell and no colour-bar panel (the viewer draws its
  /// own legend over a map layer of exactly the raster's bounds).
  bool legend = true;
};

/// The clip a style gives a heat map, metres (> 0).
double heat_map_clip(const HeatMap& map, const HeatMapStyle& style = {});

/// The colour-bar title of a quantity: "error m", "std m", "pair dist m".
std::string quantity_label(const std::string& quantity);

/// The heat map as a picture, one pixel per raster cell (north up: cell rows from the bottom
/// drawn from the image's bottom): values through the viridis table from 0 to the clip,
/// unknown cells transparent, the plan's occupied cells (when `plan` is given and shares the
/// raster's size) dark grey on top; and, on the right, a white panel with the colour bar, its
/// title (the quantity in metres), ticks at 0, half the clip and the clip ("+": and more), and
/// how the clip was chosen ("clip p95" or "clip set").
RgbaImage render_heat_map(const HeatMap& map, const HeatMapStyle& style = {},
                          const OccupancyGrid* plan = nullptr);

/// Renders and writes a heat map PNG atomically; returns the clip used, metres.
double write_heat_map_png(const std::filesystem::path& path, const HeatMap& map,
                          const HeatMapStyle& style = {}, const OccupancyGrid* plan = nullptr);

}  // namespace floorgrid::io
