#include "floorgrid/io/formats/map_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::TempDir;
using test::write_file;

std::string pgm(int width, int height, const std::vector<int>& values) {
  std::string s = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (int v : values)
    s.push_back(static_cast<char>(v));
  return s;
}

std::string yaml(const std::string& image, const std::string& extra = "") {
  return "image: " + image +
         "\nresolution: 0.1\norigin: [1.0, 2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
         "free_thresh: 0.196\n" +
         extra;
}

using test::expect_input_error;

TEST(MapIo, RealBonnGMapMatchesHeaderAndIndependentDecoder) {
  FLOORGRID_REQUIRE_DATA("bonn/GMap/GMap.yaml");
  const LoadedMap map = read_map_yaml(test::data_path("bonn/GMap/GMap.yaml"));
  EXPECT_EQ(map.grid.width(), 604);
  EXPECT_EQ(map.grid.height(), 272);
  EXPECT_DOUBLE_EQ(map.grid.resolution(), 0.05);
  const Eigen::AlignedBox2d box = map.grid.geometry().bounds();
  EXPECT_NEAR(box.min().x(), -13.90309, 1e-9);
  EXPECT_NEAR(box.max().x(), -13.90309 + 604 * 0.05, 1e-9);
  EXPECT_NEAR(box.min().y(), -10.82778, 1e-9);
  EXPECT_NEAR(box.max().y(), -10.82778 + 272 * 0.05, 1e-9);

  // Class counts from an independent decoder (python's zlib) and the ROS rule.
  const auto run = test::run_command(std::string("python3 '") + FLOORGRID_SOURCE_DIR +
                                     "/tests/tools/png_histogram.py' '" +
                                     test::data_path("bonn/GMap/GMap.png").string() + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto histogram = nlohmann::json::parse(run.out);
  std::size_t free = 0, occupied = 0, unknown = 0;
  for (const auto& [grey3, count] : histogram["grey_times_3"].items()) {
    const double occ = 1.0 - std::stod(grey3) / 3.0 / 255.0;
    if (occ > 0.65) {
      occupied += count.get<std::size_t>();
    } else if (occ < 0.196) {
      free += count.get<std::size_t>();
    } else {
      unknown += count.get<std::size_t>();
    }
  }
  const CellCounts counts = map.grid.counts();
  EXPECT_EQ(counts.occupied, occupied);
  EXPECT_EQ(counts.free, free);
  EXPECT_EQ(counts.unknown, unknown);
  EXPECT_GT(occupied, 1000u);
}

TEST(MapIo, RealBonnPgmMapsRead) {
  FLOORGRID_REQUIRE_DATA("bonn/Faro/FMap.yaml");
  const LoadedMap faro = read_map_yaml(test::data_path("bonn/Faro/FMap.yaml"));
  EXPECT_EQ(faro.grid.width(), 521);
  EXPECT_EQ(faro.grid.height(), 279);
  EXPECT_NEAR(faro.grid.geometry().origin.x, -13.9155, 1e-12);
  const LoadedMap youbot = read_map_yaml(test::data_path("bonn/2021_10_27/YouBotMap.yaml"));
  EXPECT_EQ(youbot.grid.width(), 576);
  EXPECT_EQ(youbot.grid.height(), 960);
  EXPECT_GT(youbot.grid.counts().occupied, 0u);
}

TEST(MapIo, PixelCentreFormulaWithYaw) {
  TempDir dir;
  write_file(dir / "m.pgm", pgm(3, 2, {0, 254, 205, 254, 254, 0}));
  write_file(dir / "m.yaml",
             "image: m.pgm\nresolution: 0.5\norigin: [10.0, -4.0, 1.5707963267948966]\n"
             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap map = read_map_yaml(dir / "m.yaml");
  const GridGeometry& g = map.grid.geometry();
  // Pixel (col 0, row 0) is the top-left pixel of a 2-row image: cell (0, 1).
  EXPECT_EQ(map.grid.state(0, 1), CellState::occupied);
  EXPECT_EQ(map.grid.state(2, 0), CellState::occupied);  // bottom-right pixel
  EXPECT_EQ(map.grid.state(2, 1), CellState::unknown);
  EXPECT_EQ(map.grid.state(1, 0), CellState::free);
  // origin + R(yaw) * res * (col + 0.5, H - 1 - row + 0.5) for col 2, row 0 (H = 2): yaw 90 degrees
  // turns (1.25, 0.75) into (-0.75, 1.25).
  const Eigen::Vector2d c = g.cell_center(2, g.image_row(0));
  EXPECT_NEAR(c.x(), 10.0 - 0.75, 1e-12);
  EXPECT_NEAR(c.y(), -4.0 + 1.25, 1e-12);
  int ix = -1, iy = -1;
  ASSERT_TRUE(g.cell_of(c, ix, iy));
  EXPECT_EQ(ix, 2);
  EXPECT_EQ(iy, 1);
}

TEST(MapIo, TrinaryThresholdsAreStrictAndNegateFlips) {
  TempDir dir;
  // occ = (255 - v) / 255: v=89 -> 0.651 (occupied), v=90 -> 0.647 (unknown),
  // v=205 -> 0.196078 (unknown: not < 0.196), v=206 -> 0.192 (free).
  write_file(dir / "t.pgm", pgm(4, 1, {89, 90, 205, 206}));
  write_file(dir / "t.yaml", yaml("t.pgm"));
  const LoadedMap map = read_map_yaml(dir / "t.yaml");
  EXPECT_EQ(map.grid.state(0, 0), CellState::occupied);
  EXPECT_EQ(map.grid.state(1, 0), CellState::unknown);
  EXPECT_EQ(map.grid.state(2, 0), CellState::unknown);
  EXPECT_EQ(map.grid.state(3, 0), CellState::free);

  write_file(dir / "n.yaml",
             "image: t.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\n"
             "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap negated = read_map_yaml(dir / "n.yaml");
  // occ = v / 255: 89 -> 0.349 unknown, 206 -> 0.808 occupied
  EXPECT_EQ(negated.grid.state(0, 0), CellState::unknown);
  EXPECT_EQ(negated.grid.state(3, 0), CellState::occupied);
}

TEST(MapIo, RgbIsMeanAndOnlyFullyTransparentIsUnknown) {
  TempDir dir;
  // Pure blue: mean 85 -> occ 0.667; luminance weighting would give 0.886.
  write_png_rgb(dir / "c.png", 1, 1, {0, 0, 255});
  write_file(dir / "c.yaml",
             "image: c.png\nresolution: 1\norigin: [0,0,0]\nnegate: 0\n"
             "occupied_thresh: 0.7\nfree_thresh: 0.1\n");
  EXPECT_EQ(read_map_yaml(dir / "c.yaml").grid.state(0, 0), CellState::unknown);

  // Dark pixels: opaque, half transparent, fully transparent.
  write_png(dir / "a.png", 3, 1, {0, 0, 0}, {255, 128, 0});
  write_file(dir / "a.yaml", yaml("a.png"));
  const LoadedMap map = read_map_yaml(dir / "a.yaml");
  EXPECT_EQ(map.grid.state(0, 0), CellState::occupied);
  EXPECT_EQ(map.grid.state(1, 0), CellState::occupied);  // ROS trinary would blend alpha in
  EXPECT_EQ(map.grid.state(2, 0), CellState::unknown);
}

TEST(MapIo, ScaleModeFollowsNav2) {
  TempDir dir;
  // occ 0.4 with thresholds 0.25/0.65 -> rint(0.15 / 0.4 * 100) = 38 (kept as value, class unknown)
  const int v = static_cast<int>(std::lround(255 * 0.6));
  write_png(dir / "s.png", 3, 1, {static_cast<std::uint8_t>(v), 0, 255}, {255, 255, 200});
  write_file(dir / "s.yaml",
             "image: s.png\nmode: scale\nresolution: 1\norigin: [0,0,0]\n"
             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n");
  const LoadedMap map = read_map_yaml(dir / "s.yaml");
  const double occ = 1.0 - v / 255.0;
  EXPECT_EQ(map.grid.value(0, 0), static_cast<int>(std::rint((occ - 0.25) / 0.4 * 100.0)));
  EXPECT_EQ(map.grid.state(0, 0), CellState::unknown);
  EXPECT_EQ(map.grid.state(1, 0), CellState::occupied);
  EXPECT_EQ(map.grid.state(2, 0), CellState::unknown);  // white but not opaque
  EXPECT_EQ(map.grid.value(2, 0), -1);
}

TEST(MapIo, RawModeRoundTripsBytesExactly) {
  TempDir dir;
  std::vector<int> values;
  for (int i = 0; i < 12; ++i)
    values.push_back(i < 11 ? i * 10 : 255);
  const std::string original = pgm(4, 3, values);
  write_file(dir / "r.pgm", original);
  write_file(dir / "r.yaml",
             "image: r.pgm\nmode: raw\nresolution: 0.05\norigin: [0,0,0]\n"
             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap map = read_map_yaml(dir / "r.yaml");
  EXPECT_EQ(map.grid.value(0, 2), 0);  // top-left pixel is the top row
  EXPECT_EQ(map.grid.value(3, 1), 70);
  EXPECT_EQ(map.grid.state(3, 1), CellState::occupied);
  EXPECT_EQ(map.grid.value(3, 0), -1);  // 255 is beyond 100: unknown
  MapWriteOptions options;
  options.mode = MapMode::raw;
  const auto image = write_map(map.grid, dir / "out.yaml", options);
  EXPECT_EQ(test::read_file(image), original);
}

TEST(MapIo, WriteThenReadKeepsClassesAndFrame) {
  GridGeometry g{7, 5, 0.05, {-3.25, 8.5, 0.3}};
  OccupancyGrid grid(g);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      grid.set_state(ix, iy, static_cast<CellState>((ix * 3 + iy * 5) % 3));
    }
  }
  TempDir dir;
  for (const auto& [mode, format] :
       std::vector<std::pair<MapMode, std::string>>{{MapMode::trinary, "pgm"},
                                                    {MapMode::trinary, "png"},
                                                    {MapMode::scale, "png"},
                                                    {MapMode::raw, "pgm"}}) {
    MapWriteOptions options;
    options.mode = mode;
    options.image_format = format;
    options.free_thresh = 0.25;  // nav2's default: 205 would read back as free, so 205 is not used
    const auto yaml_path = dir / ("m-" + to_string(mode) + "-" + format + ".yaml");
    write_map(grid, yaml_path, options);
    const LoadedMap back = read_map_yaml(yaml_path);
    EXPECT_EQ(back.grid.states(), grid.states()) << to_string(mode) << " " << format;
    EXPECT_EQ(back.grid.width(), 7);
    EXPECT_DOUBLE_EQ(back.grid.geometry().origin.x, -3.25);
    EXPECT_DOUBLE_EQ(back.grid.geometry().origin.y, 8.5);
    EXPECT_DOUBLE_EQ(back.grid.geometry().origin.theta, 0.3);
    EXPECT_DOUBLE_EQ(back.grid.resolution(), 0.05);
  }
}

TEST(MapIo, BareImageNeedsResolution) {
  FLOORGRID_REQUIRE_DATA("fr079/slam_map.png");
  const auto path = test::data_path("fr079/slam_map.png");
  expect_input_error([&] { read_map(path, std::nullopt, std::nullopt, "gridmap"); },
                     {"slam_map.png", "gridmap_resolution"});
  const LoadedMap map = read_map(path, 0.05, Pose2{1.0, 2.0, 0.0}, "gridmap");
  EXPECT_EQ(map.grid.width(), 700);
  EXPECT_EQ(map.grid.height(), 289);
  EXPECT_NEAR(map.grid.geometry().bounds().max().x(), 1.0 + 700 * 0.05, 1e-9);
  EXPECT_GT(map.grid.counts().occupied, 0u);
}

TEST(MapIo, BadYamlIsRefusedNamingFileLineAndField) {
  TempDir dir;
  write_file(dir / "ok.pgm", pgm(2, 2, {0, 0, 0, 0}));
  const auto check = [&](const std::string& name, const std::string& text,
                         const std::vector<std::string>& parts) {
    write_file(dir / name, text);
    auto expected = parts;
    expected.push_back(name);
    expect_input_error([&] { read_map_yaml(dir / name); }, expected);
  };
  check("no_image.yaml",
        "resolution: 0.1\norigin: [0,0,0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\n",
        {"'image'", "missing"});
  // An image name too long for the file system threw std::filesystem_error (found by fuzzing).
  check("long_name.yaml",
        "image: " + std::string(5000, 'x') +
            "\nresolution: 0.1\norigin: [0,0,0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\n",
        {"'image'", "does not exist"});
  check("no_res.yaml", "image: ok.pgm\norigin: [0,0,0]\noccupied_thresh: 0.65\nfree_thresh: 0.2\n",
        {"'resolution'", "missing"});
  check("bad_res.yaml", yaml("ok.pgm").replace(yaml("ok.pgm").find("0.1"), 3, "abc"),
        {":2:", "'resolution'", "abc"});
  check("neg_res.yaml", yaml("ok.pgm").replace(yaml("ok.pgm").find("0.1"), 3, "-0.1"),
        {"'resolution'", "0.0001 to 100 metres per pixel"});
  check("origin2.yaml",
        "image: ok.pgm\nresolution: 0.1\norigin: [0, 0]\noccupied_thresh: 0.65\n"
        "free_thresh: 0.2\n",
        {":3:", "'origin'", "3 numbers"});
  check("thresh.yaml",
        "image: ok.pgm\nresolution: 0.1\norigin: [0,0,0]\noccupied_thresh: 0.2\n"
        "free_thresh: 0.65\n",
        {"'free_thresh'"});
  check("mode.yaml", yaml("ok.pgm", "mode: fancy\n"), {":7:", "'mode'", "fancy"});
  check("syntax.yaml", "image: ok.pgm\nresolution: [0.1\n", {"syntax"});
  check("noimage.yaml", yaml("missing.pgm"), {"'image'", "does not exist"});
  check("empty.yaml", "", {"empty"});
}

TEST(MapIo, BadImagesAreRefusedWithoutAllocating) {
  TempDir dir;
  const auto check = [&](const std::string& name, const std::string& bytes,
                         const std::vector<std::string>& parts) {
    write_file(dir / name, bytes);
    auto expected = parts;
    expected.push_back(name);
    expect_input_error([&] { read_grey_image(dir / name); }, expected);
  };
  check("huge.pgm", "P5\n1000000 1000000\n255\n\x01\x02", {"too large", "coarser resolution"});
  // 31,000 x 31,000 passes the side limit but not the pixel count (it took 6.4 GB).
  check("wide.pgm", "P5\n31000 31000\n255\n\x01\x02", {"31000 x 31000", "too large"});
  check("trunc.pgm", pgm(10, 10, std::vector<int>(50, 1)), {"truncated", "100 bytes"});
  check("magic.pgm", "GIF89a....", {"magic"});
  check("maxval.pgm", "P5\n2 2\n0\n\x00\x00\x00\x00", {"maxval"});
  check("badwidth.pgm", "P5\nwide 2\n255\n", {"width"});
  check("ascii.pgm", "P2\n2 2\n255\n0 1 2\n", {"truncated"});
  check("empty.pgm", "", {"empty"});
  // A real PNG cut in half.
  write_png(dir / "full.png", 64, 64, std::vector<std::uint8_t>(64 * 64, 7));
  const std::string png = test::read_file(dir / "full.png");
  check("cut.png", png.substr(0, png.size() / 2), {"PNG"});
  // A PNG header claiming a huge image.
  std::string huge_png = png;
  huge_png[16] = 0x7f;  // width's top byte in IHDR
  check("huge.png", huge_png, {"PNG"});
}

TEST(MapIo, AsciiPgmAndSixteenBitPgmRead) {
  TempDir dir;
  write_file(dir / "a.pgm", "P2\n# comment\n2 1\n15\n0 15\n");
  const GreyImage a = read_grey_image(dir / "a.pgm");
  EXPECT_DOUBLE_EQ(a.shade(0), 0.0);
  EXPECT_DOUBLE_EQ(a.shade(1), 1.0);
  std::string sixteen = "P5\n1 1\n65535\n";
  sixteen += '\x80';
  sixteen += '\x00';
  write_file(dir / "b.pgm", sixteen);
  EXPECT_NEAR(read_grey_image(dir / "b.pgm").shade(0), 32768.0 / 65535.0, 1e-12);
}

}  // namespace
}  // namespace floorgrid::io
