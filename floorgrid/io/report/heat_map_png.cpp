#include "floorgrid/io/report/heat_map_png.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/report/viridis.hpp"

namespace floorgrid::io {

namespace {

using Rgba = std::array<std::uint8_t, 4>;

constexpr Rgba kWhite = {255, 255, 255, 255};
constexpr Rgba kBlack = {0, 0, 0, 255};
constexpr Rgba kWall = {64, 64, 64, 255};

/// The smallest of 1, 2, 2.5, 5 times a power of ten that is >= v (v > 0).
double nice_ceiling(double v) {
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (const double step : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (step * decade >= v * (1.0 - 1e-12))
      return step * decade;
  }
  return 10.0 * decade;
}

Rgba colour_of(double value, double clip) {
  const double t = std::clamp(value / clip, 0.0, 1.0);
  const auto& c = viridis()[static_cast<std::size_t>(std::lround(255.0 * t))];
  return {c[0], c[1], c[2], 255};
}

/// Tick text: enough decimals to tell the clip apart.
std::string tick(double value, double clip) {
  const int decimals = clip >= 1.0 ? 1 : clip >= 0.1 ? 2 : clip >= 0.01 ? 3 : 4;
  return value == 0.0 ? "0" : fmt::format("{:.{}f}", value, decimals);
}

}  // namespace

double heat_map_clip(const HeatMap& map, const HeatMapStyle& style) {
  if (style.clip_m > 0.0)
    return style.clip_m;
  return nice_ceiling(std::max(map.quantile(style.quantile), style.min_clip_m));
}

std::string quantity_label(const std::string& quantity) {
  if (quantity == "error_m")
    return "error m";
  if (quantity == "std_m")
    return "std m";
  if (quantity == "nearest_pair_m")
    return "pair dist m";
  return quantity;
}

namespace {

RgbaImage render_with_clip(const HeatMap& map, double clip, const HeatMapStyle& style,
                           const OccupancyGrid* plan) {
  const int w = map.raster.width, h = map.raster.height;
  // The panel's scale: labels readable beside a map of any size.
  const int s = std::max(1, static_cast<int>(std::lround(h / 300.0)));
  const std::string title = quantity_label(map.quantity);
  const std::string top = tick(clip, clip) + "+";
  const std::string note =
      style.clip_m > 0.0 ? "clip set" : fmt::format("clip p{:.0f}", 100.0 * style.quantile);
  const std::size_t longest = std::max({title.size(), top.size(), note.size()});
  const int glyph_w = BitmapFont::kAdvance * s, line_h = (BitmapFont::kHeight + 3) * s;
  const int margin = 4 * s, bar_w = 8 * s;
  const int panel_w = std::max<int>(margin + bar_w + 3 * s + 6 * glyph_w + margin,
                                    2 * margin + static_cast<int>(longest) * glyph_w);
  const int height = style.legend ? std::max(h, 2 * margin + 3 * line_h + 40 * s) : h;

  RgbaImage image{style.legend ? w + panel_w : w, height, {}};
  image.rgba.assign(static_cast<std::size_t>(image.width) * image.height * 4, 0);
  const int top_pad = height - h;  // a short map sits at the bottom of a taller panel
  const bool walls = plan && plan->width() == w && plan->height() == h;
  for (int iy = 0; iy < h; ++iy) {
    const int row = top_pad + (h - 1 - iy);
    for (int ix = 0; ix < w; ++ix) {
      const float v = map.values[static_cast<std::size_t>(iy) * w + ix];
      if (walls && plan->state(ix, iy) == CellState::occupied)
        image.set(ix, row, kWall);
      else if (std::isfinite(v))
        image.set(ix, row, colour_of(v, clip));
    }
  }
  if (!style.legend)
    return image;

  // The panel: title, bar with ticks, how the clip was chosen.
  for (int row = 0; row < height; ++row)
    for (int col = w; col < image.width; ++col)
      image.set(col, row, kWhite);
  const int left = w + margin;
  draw_text(image, left, margin, title, s, kBlack);
  const int bar_top = margin + line_h + BitmapFont::kHeight * s / 2;
  const int bar_bottom = height - margin - line_h - BitmapFont::kHeight * s / 2;
  for (int row = bar_top; row <= bar_bottom; ++row) {
    const double t = static_cast<double>(bar_bottom - row) / std::max(1, bar_bottom - bar_top);
    for (int col = left; col < left + bar_w; ++col)
      image.set(col, row, colour_of(t * clip, clip));
  }
  const int text_left = left + bar_w + 3 * s;
  const int half_glyph = BitmapFont::kHeight * s / 2;
  draw_text(image, text_left, bar_top - half_glyph, top, s, kBlack);
  draw_text(image, text_left, (bar_top + bar_bottom) / 2 - half_glyph, tick(clip / 2, clip), s,
            kBlack);
  draw_text(image, text_left, bar_bottom - half_glyph, "0", s, kBlack);
  draw_text(image, left, height - margin - BitmapFont::kHeight * s, note, s, kBlack);
  return image;
}

}  // namespace

RgbaImage render_heat_map(const HeatMap& map, const HeatMapStyle& style,
                          const OccupancyGrid* plan) {
  return render_with_clip(map, heat_map_clip(map, style), style, plan);
}

double write_heat_map_png(const std::filesystem::path& path, const HeatMap& map,
                          const HeatMapStyle& style, const OccupancyGrid* plan) {
  const double clip = heat_map_clip(map, style);
  const RgbaImage image = render_with_clip(map, clip, style, plan);
  write_png_rgba(path, image.width, image.height, image.rgba);
  return clip;
}

}  // namespace floorgrid::io
