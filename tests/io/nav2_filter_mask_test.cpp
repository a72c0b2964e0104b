// nav2's conventions for filter masks and waypoints: the mask loads with our map reader exactly as
// the gridmap does (size, origin, resolution), and its pixels, decoded with nav2 map_server's
// formula for the mask's mode (written out here independently of the writer), give the
// OccupancyGrid values nav2's KeepoutFilter and SpeedFilter read; the filter-info params; the
// FollowWaypoints poses.
#include "floorgrid/io/formats/nav2_filter_mask.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;

/// A gridmap of 80 x 60 cells of 0.05 m from (-1.3, -0.7), with a yaw of 0.
GridGeometry gridmap() {
  GridGeometry g;
  g.width = 80;
  g.height = 60;
  g.resolution = 0.05;
  g.origin = {-1.3, -0.7, 0.0};
  return g;
}

/// nav2_map_server map_io.cpp (loadMapFromFile), negate 0, opaque grey pixel:
///   occ = 1 - pixel / 255
///   trinary: occupied_thresh < occ -> 100; occ < free_thresh -> 0; else -1
///   scale:   the same outside the thresholds, else rint((occ - free) / (occupied - free) * 100)
int nav2_decode(int pixel, const std::string& mode, double occupied, double free) {
  const double occ = 1.0 - pixel / 255.0;
  if (occupied < occ)
    return 100;
  if (occ < free)
    return 0;
  if (mode == "trinary")
    return -1;
  return static_cast<int>(std::rint((occ - free) / (occupied - free) * 100.0));
}

/// The square [0.5, 1.5] x [0.5, 1.25] plan metres, shifted by (-0.3, 0.2) on the gridmap.
Zone square(double percent = 0.0) {
  Zone z;
  z.name = "bay";
  z.outer = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.25}, {0.5, 1.25}};
  if (percent > 0)
    z.speed.percent = percent;
  return z;
}

std::unique_ptr<PointMapping> shift_model() {
  return test::fitted("gt",
                      test::lattice_pairs(KnownSimilarity{1.0, 0.0, {-0.3, 0.2}}, -1, 3, -1, 3));
}

/// Reads back a written mask: our reader's grid, and nav2's decoding of each pixel (top row
/// first) from the YAML's mode and thresholds.
struct ReadBack {
  io::LoadedMap map;
  std::vector<int> nav2;  ///< OccupancyGrid values, row-major from the bottom row as the grid
};

ReadBack read_back(const std::filesystem::path& yaml) {
  ReadBack r{io::read_map_yaml(yaml), {}};
  const io::GreyImage image = io::read_grey_image(r.map.image_path);
  EXPECT_EQ(image.max_level, 255);
  const io::MapMetadata& m = r.map.metadata;
  const std::string mode = io::to_string(m.mode);
  r.nav2.resize(image.level.size());
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const int pixel = image.level[static_cast<std::size_t>(row) * image.width + col];
      const int iy = image.height - 1 - row;
      r.nav2[static_cast<std::size_t>(iy) * image.width + col] =
          nav2_decode(pixel, mode, m.occupied_thresh, m.free_thresh);
    }
  }
  return r;
}

/// Whether cell (ix, iy)'s centre lies inside the shifted square.
bool in_square(const GridGeometry& g, int ix, int iy) {
  const Eigen::Vector2d c = g.cell_center(ix, iy);
  return c.x() >= 0.2 && c.x() < 1.2 && c.y() >= 0.7 && c.y() < 1.45;
}

TEST(Nav2FilterMask, AKeepoutMaskLoadsLikeTheGridmapAndReadsOneHundredInTheZone) {
  test::TempDir dir;
  const auto model = shift_model();
  ZoneMaskOptions options;
  options.margin_sigma = 0.0;
  const ZoneMask mask =
      map_zones_to_mask(*model, {square()}, gridmap(), ZoneMaskKind::keepout, options);
  const io::Nav2MaskFiles files = io::nav2_mask_files(mask, "keepout_mask");
  const auto yaml = io::write_nav2_mask_files(files, dir.path());
  EXPECT_EQ(yaml, dir / "keepout_mask.yaml");
  const std::string text = test::read_file(yaml);
  for (const char* line : {"image: keepout_mask.pgm\n", "mode: trinary\n", "resolution: 0.05\n",
                           "origin: [-1.3, -0.7, 0]\n", "negate: 0\n", "occupied_thresh: 0.65\n",
                           "free_thresh: 0.196\n"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " in\n" << text;
  }
  const ReadBack back = read_back(yaml);
  const GridGeometry& g = back.map.grid.geometry();
  EXPECT_EQ(g.width, 80);
  EXPECT_EQ(g.height, 60);
  EXPECT_DOUBLE_EQ(g.resolution, 0.05);
  EXPECT_DOUBLE_EQ(g.origin.x, -1.3);
  EXPECT_DOUBLE_EQ(g.origin.y, -0.7);
  EXPECT_DOUBLE_EQ(g.origin.theta, 0.0);
  std::size_t inside = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const int expected = in_square(g, ix, iy) ? 100 : 0;
      inside += expected == 100;
      ASSERT_EQ(back.nav2[static_cast<std::size_t>(iy) * g.width + ix], expected)
          << ix << ", " << iy;
      ASSERT_EQ(back.map.grid.state(ix, iy),
                expected == 100 ? CellState::occupied : CellState::free);
    }
  }
  EXPECT_EQ(inside, 20u * 15u);  // 1 m x 0.75 m of 5 cm cells
  const std::string params = test::read_file(dir / "keepout_mask_filter_info.yaml");
  for (const char* line :
       {"costmap_filter_info_server:\n", "    type: 0\n", "    base: 0\n", "    multiplier: 1\n",
        "    mask_topic: \"/keepout_mask\"\n", "    topic_name: \"/keepout_mask\"\n",
        "    yaml_filename: \"keepout_mask.yaml\"\n", "filter_mask_server:\n"}) {
    EXPECT_NE(params.find(line), std::string::npos) << line << " in\n" << params;
  }
}

TEST(Nav2FilterMask, ASpeedMaskReadsItsPercentThroughBaseAndMultiplier) {
  test::TempDir dir;
  const auto model = shift_model();
  ZoneMaskOptions options;
  options.margin_sigma = 0.0;
  const ZoneMask mask =
      map_zones_to_mask(*model, {square(35.0)}, gridmap(), ZoneMaskKind::speed, options);
  const auto yaml = io::write_nav2_mask_files(io::nav2_mask_files(mask, "speed_mask"), dir.path());
  const std::string text = test::read_file(yaml);
  for (const char* line : {"mode: scale\n", "occupied_thresh: 1\n", "free_thresh: 0\n"})
    EXPECT_NE(text.find(line), std::string::npos) << line << " in\n" << text;
  const ReadBack back = read_back(yaml);
  const std::string params = test::read_file(dir / "speed_mask_filter_info.yaml");
  EXPECT_NE(params.find("    type: 1\n"), std::string::npos) << params;
  const GridGeometry& g = back.map.grid.geometry();
  EXPECT_EQ(g.width, 80);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const int value = back.nav2[static_cast<std::size_t>(iy) * g.width + ix];
      // SpeedFilter: 0 = no limit; else speed_limit = base + multiplier * value = 35 %.
      ASSERT_EQ(value, in_square(g, ix, iy) ? 35 : 0) << ix << ", " << iy;
      ASSERT_EQ(back.map.grid.value(ix, iy), value) << "our reader agrees with nav2's formula";
    }
  }
}

TEST(Nav2FilterMask, EveryValueOfEveryModeDecodesBackThroughNav2sFormula) {
  for (const auto& [mode, occupied, free] :
       {std::tuple{io::MapMode::scale, 1.0, 0.0}, std::tuple{io::MapMode::scale, 0.65, 0.196},
        std::tuple{io::MapMode::trinary, 0.65, 0.196},
        std::tuple{io::MapMode::trinary, 0.65, 0.25}}) {
    io::MapMetadata m;
    m.mode = mode;
    m.occupied_thresh = occupied;
    m.free_thresh = free;
    const std::string name = io::to_string(mode);
    for (int v = -1; v <= 100; ++v) {
      if (mode == io::MapMode::trinary && v > 0 && v < 100)
        continue;
      if (mode == io::MapMode::scale && v < 0)
        continue;  // scale's unknown is transparency
      const int pixel = io::nav2_mask_pixel(static_cast<std::int8_t>(v), m);
      EXPECT_EQ(nav2_decode(pixel, name, occupied, free), v) << name << " " << free << " " << v;
    }
  }
}

TEST(Nav2FilterMask, WaypointsAreFollowWaypointsPosesWithTheirHeadingAndFlags) {
  MappedWaypoint dock;
  dock.waypoint.name = "dock";
  dock.waypoint.position = {1.5, -2.25};
  dock.waypoint.theta = M_PI / 2;
  dock.std_m = 0.031;
  MappedWaypoint far;
  far.waypoint.name = "far";
  far.waypoint.position = {40.0, 3.0};
  far.flag = MapFlag::extrapolated;
  far.extrapolated = true;
  const std::string yaml = io::nav2_waypoints_yaml({dock, far});
  for (const char* line :
       {"poses:\n", "  # dock: std_m 0.031, flag ok\n", "  - header: {frame_id: \"map\"}\n",
        "      position: {x: 1.5000, y: -2.2500, z: 0.0}\n",
        "      orientation: {x: 0.0, y: 0.0, z: 0.707106781, w: 0.707106781}\n",
        "  # far: std_m none, flag extrapolated, EXTRAPOLATED, no heading given",
        "      orientation: {x: 0.0, y: 0.0, z: 0.000000000, w: 1.000000000}\n"}) {
    EXPECT_NE(yaml.find(line), std::string::npos) << line << " in\n" << yaml;
  }
}

}  // namespace
}  // namespace floorgrid
