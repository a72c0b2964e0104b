// The heat maps' pictures: the viridis table (its ends, rising lightness), values through it up
// to the clip, unknown cells transparent, the colour bar's panel and labels, the PNG file.
#include "floorgrid/io/report/heat_map_png.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/report/viridis.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

/// CIELAB lightness L* of an sRGB colour.
double lightness(const std::array<std::uint8_t, 3>& c) {
  const auto linear = [](double u) {
    u /= 255.0;
    return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4);
  };
  const double y = 0.2126 * linear(c[0]) + 0.7152 * linear(c[1]) + 0.0722 * linear(c[2]);
  return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : 24389.0 / 27.0 * y;
}

HeatMap ramp(int width, int height, double top) {
  HeatMap map;
  map.raster.width = width;
  map.raster.height = height;
  map.raster.resolution = 0.05;
  map.quantity = "error_m";
  map.values.resize(map.raster.size());
  for (std::size_t i = 0; i < map.values.size(); ++i)
    map.values[i] = static_cast<float>(top * static_cast<double>(i) / map.values.size());
  return map;
}

std::array<std::uint8_t, 4> pixel(const RgbaImage& image, int col, int row) {
  const std::size_t i = (static_cast<std::size_t>(row) * image.width + col) * 4;
  return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2], image.rgba[i + 3]};
}

TEST(Viridis, EndsAreDarkVioletAndYellow) {
  const ColourTable& t = viridis();
  // matplotlib's viridis runs from #440154 to #fde725; the polynomial fit is within a few levels.
  EXPECT_NEAR(t.front()[0], 0x44, 4);
  EXPECT_NEAR(t.front()[1], 0x01, 4);
  EXPECT_NEAR(t.front()[2], 0x54, 4);
  EXPECT_NEAR(t.back()[0], 0xfd, 4);
  EXPECT_NEAR(t.back()[1], 0xe7, 4);
  EXPECT_NEAR(t.back()[2], 0x25, 12);
}

TEST(Viridis, LightnessRisesThroughTheTable) {
  const ColourTable& t = viridis();
  // Steps of one entry may dip by the 8-bit rounding (< 0.1 L*); steps of eight always rise.
  for (std::size_t i = 1; i < t.size(); ++i)
    EXPECT_GT(lightness(t[i]) - lightness(t[i - 1]), -0.1) << i;
  for (std::size_t i = 8; i < t.size(); i += 8)
    EXPECT_GT(lightness(t[i]), lightness(t[i - 8])) << i;
  EXPECT_LT(lightness(t.front()), 20.0);
  EXPECT_GT(lightness(t.back()), 85.0);
}

TEST(HeatMapPng, AutomaticClipIsTheNinetyFifthPercentileRoundedUp) {
  EXPECT_DOUBLE_EQ(heat_map_clip(ramp(100, 10, 0.43 / 0.95)), 0.5);
  EXPECT_DOUBLE_EQ(heat_map_clip(ramp(100, 10, 0.019 / 0.95)), 0.02);
  EXPECT_DOUBLE_EQ(heat_map_clip(ramp(100, 10, 0.24 / 0.95)), 0.25);
  HeatMapStyle set;
  set.clip_m = 0.3;
  EXPECT_DOUBLE_EQ(heat_map_clip(ramp(100, 10, 5.0), set), 0.3);
}

TEST(HeatMapPng, WithoutTheLegendThePictureIsTheRasterAlonePixelForPixel) {
  HeatMap map = ramp(200, 120, 1.0);
  map.values[0] = std::numeric_limits<float>::quiet_NaN();
  HeatMapStyle style;
  style.clip_m = 0.5;
  const RgbaImage with = render_heat_map(map, style);
  style.legend = false;
  const RgbaImage without = render_heat_map(map, style);
  ASSERT_EQ(without.width, 200);
  ASSERT_EQ(without.height, 120);
  // The same pixels as the map part of the picture with its legend.
  for (int row = 0; row < 120; ++row) {
    for (int col = 0; col < 200; col += 7) {
      EXPECT_EQ(pixel(without, col, row), pixel(with, col, row)) << col << ", " << row;
    }
  }
  EXPECT_EQ(pixel(without, 0, 119)[3], 0);
}

TEST(HeatMapPng, ValuesGoThroughViridisUnknownIsTransparentAndThePanelIsBeside) {
  HeatMap map = ramp(200, 120, 1.0);
  map.values[0] = std::numeric_limits<float>::quiet_NaN();  // cell (0, 0): bottom-left pixel
  map.values[1] = 0.0f;
  map.values[2] = 0.25f;
  map.values[3] = 7.0f;  // far above the clip
  HeatMapStyle style;
  style.clip_m = 0.5;
  const RgbaImage image = render_heat_map(map, style);
  EXPECT_GT(image.width, 200);
  EXPECT_EQ(image.height, 120);
  const int bottom = image.height - 1;
  EXPECT_EQ(pixel(image, 0, bottom)[3], 0);
  const auto expect = [&](int col, std::size_t entry) {
    const auto p = pixel(image, col, bottom);
    EXPECT_EQ(p[0], viridis()[entry][0]) << col;
    EXPECT_EQ(p[1], viridis()[entry][1]) << col;
    EXPECT_EQ(p[2], viridis()[entry][2]) << col;
    EXPECT_EQ(p[3], 255) << col;
  };
  expect(1, 0);
  expect(2, 128);  // 0.25 / 0.5 of 255, rounded
  expect(3, 255);
  // The panel is opaque white with black text and the bar's colours.
  std::size_t black = 0, coloured = 0;
  for (int row = 0; row < image.height; ++row) {
    for (int col = 200; col < image.width; ++col) {
      const auto p = pixel(image, col, row);
      EXPECT_EQ(p[3], 255);
      black += p[0] == 0 && p[1] == 0 && p[2] == 0 ? 1 : 0;
      coloured += p[0] != p[1] || p[1] != p[2] ? 1 : 0;
    }
  }
  EXPECT_GT(black, 100u);
  EXPECT_GT(coloured, 100u);
}

TEST(HeatMapPng, LabelsAreDrawableAndThePlanWallsShow) {
  for (const char* label :
       {"error m", "std m", "pair dist m", "clip p95", "clip set", "0.50+", "0.0125", "1.5+"}) {
    for (const char* c = label; *c != 0; ++c)
      EXPECT_TRUE(*c == ' ' || BitmapFont::has(*c)) << label << ": '" << *c << "'";
  }
  HeatMap map = ramp(50, 40, 1.0);
  GridGeometry g = map.raster;
  OccupancyGrid plan(g, CellState::free);
  plan.set_state(5, 0, CellState::occupied);
  const RgbaImage image = render_heat_map(map, {}, &plan);
  const auto p = pixel(image, 5, image.height - 1);
  EXPECT_EQ(p[0], 64);
  EXPECT_EQ(p[3], 255);
}

TEST(HeatMapPng, WritesAnRgbaPng) {
  test::TempDir dir;
  HeatMap map = ramp(64, 48, 0.2);
  map.values[10] = std::numeric_limits<float>::quiet_NaN();
  const double clip = write_heat_map_png(dir / "heat.png", map);
  EXPECT_GT(clip, 0.0);
  const GreyImage read = read_grey_image(dir / "heat.png");
  EXPECT_GT(read.width, 64);
  EXPECT_GE(read.height, 48);  // a short map sits at the bottom of its colour bar's panel
  ASSERT_TRUE(read.has_alpha());
  const std::size_t bottom_row = static_cast<std::size_t>(read.height - 1) * read.width;
  EXPECT_EQ(read.alpha[bottom_row + 10], 0);
  EXPECT_EQ(read.alpha[bottom_row + 11], 255);
}

}  // namespace
}  // namespace floorgrid::io
