// nav2 map of the plan's walls: a known square room through a known similarity lands on the
// expected cells.
#include "floorgrid/io/export/export_nav2_map.hpp"

#include <gtest/gtest.h>

#include <set>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;

/// A 4 m square room, corners (0, 0) and (4, 4).
VectorFloorplan square_room() {
  VectorFloorplan room;
  room.add_segment({0, 0}, {4, 0}, "WALLS");
  room.add_segment({4, 0}, {4, 4}, "WALLS");
  room.add_segment({4, 4}, {0, 4}, "WALLS");
  room.add_segment({0, 4}, {0, 0}, "WALLS");
  return room;
}

/// 120 x 120 cells of 0.1 m from (-5, -5).
GridGeometry gridmap() {
  GridGeometry g;
  g.width = g.height = 120;
  g.resolution = 0.1;
  g.origin = {-5.0, -5.0, 0.0};
  return g;
}

/// The cells of the room through grid = R(90) plan + (1.02, 1.03): walls x = 1.02 and -2.98
/// for y in [1.03, 5.03], y = 1.03 and 5.03 for x in [-2.98, 1.02] (away from cell borders).
std::set<std::pair<int, int>> expected_cells() {
  std::set<std::pair<int, int>> cells;
  const auto cell = [](double v) { return static_cast<int>(std::floor((v + 5.0) / 0.1)); };
  for (int iy = cell(1.03); iy <= cell(5.03); ++iy) {
    cells.insert({cell(1.02), iy});
    cells.insert({cell(-2.98), iy});
  }
  for (int ix = cell(-2.98); ix <= cell(1.02); ++ix) {
    cells.insert({ix, cell(1.03)});
    cells.insert({ix, cell(5.03)});
  }
  return cells;
}

std::set<std::pair<int, int>> occupied(const OccupancyGrid& grid) {
  std::set<std::pair<int, int>> cells;
  for (int iy = 0; iy < grid.height(); ++iy)
    for (int ix = 0; ix < grid.width(); ++ix)
      if (grid.state(ix, iy) == CellState::occupied)
        cells.insert({ix, iy});
  return cells;
}

TEST(ExportNav2Map, ASquareRoomThroughAKnownSimilarityLandsOnTheExpectedCells) {
  const KnownSimilarity truth{1.0, M_PI / 2, {1.02, 1.03}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 4, 0, 4));
  const OccupancyGrid walls = io::plan_walls_in_grid(*model, square_room(), gridmap());
  EXPECT_EQ(occupied(walls), expected_cells());
  EXPECT_EQ(walls.counts().unknown, 0u);
  EXPECT_EQ(walls.counts().free, walls.geometry().size() - expected_cells().size());
}

TEST(ExportNav2Map, WrittenAsATrinaryMapThatReadsBack) {
  test::TempDir dir;
  const KnownSimilarity truth{1.0, M_PI / 2, {1.02, 1.03}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 4, 0, 4));
  io::Nav2MapOptions options;
  options.background = CellState::unknown;
  const OccupancyGrid walls = io::plan_walls_in_grid(*model, square_room(), gridmap(), options);
  const auto image = io::write_nav2_map(walls, dir / "walls.yaml");
  EXPECT_EQ(image.filename(), "walls.pgm");
  const std::string yaml = test::read_file(dir / "walls.yaml");
  for (const char* line :
       {"image: walls.pgm\n", "mode: trinary\n", "resolution: 0.1\n", "origin: [-5, -5, 0]\n",
        "negate: 0\n", "occupied_thresh: 0.65\n", "free_thresh: 0.25\n"}) {
    EXPECT_NE(yaml.find(line), std::string::npos) << line << " in\n" << yaml;
  }
  const io::LoadedMap back = io::read_map_yaml(dir / "walls.yaml");
  EXPECT_EQ(back.grid.width(), 120);
  EXPECT_EQ(occupied(back.grid), expected_cells());
  EXPECT_EQ(back.grid.counts().unknown, back.grid.geometry().size() - expected_cells().size());
  // The walls are black in the image (row 0 at the top).
  const io::GreyImage pgm = io::read_grey_image(image);
  const auto [ix, iy] = *expected_cells().begin();
  EXPECT_EQ(pgm.level[static_cast<std::size_t>((119 - iy) * 120 + ix)], 0);
}

TEST(ExportNav2Map, ARasterPlanThroughABentModelFollowsTheBentWalls) {
  // The room rasterized at 0.05 m, drawn through a tps of a bend: every point of the bent walls
  // has a wall cell next to it (the walls stay connected), and every wall cell lies next to the
  // bent walls (nothing stray).
  const test::BentTruth truth{{1.0, 0.0, {0.3, 0.2}}};
  const auto model = test::fitted("tps", test::lattice_pairs(truth, -1, 5, -1, 5, 13, 13));
  RasterizeOptions raster;
  raster.resolution = 0.05;
  raster.wall_thickness = 0.05;
  const OccupancyGrid plan = rasterize(square_room(), raster);
  const OccupancyGrid walls = io::plan_walls_in_grid(*model, plan, gridmap());
  const Eigen::Matrix2Xd samples = square_room().sample_points(0.01);
  std::set<std::pair<int, int>> near_walls;
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    int ix = 0, iy = 0;
    ASSERT_TRUE(gridmap().cell_of(model->forward(samples.col(i)), ix, iy));
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        near_walls.insert({ix + dx, iy + dy});
        found = found || walls.state(ix + dx, iy + dy) == CellState::occupied;
      }
    }
    EXPECT_TRUE(found) << samples.col(i).transpose();
  }
  for (const auto& cell : occupied(walls))
    EXPECT_TRUE(near_walls.count(cell)) << cell.first << ", " << cell.second;
}

TEST(ExportNav2Map, RefusesBadSampling) {
  const KnownSimilarity truth{1.0, 0.0, {0.0, 0.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 4, 0, 4));
  io::Nav2MapOptions options;
  options.samples_per_cell = 0.5;
  EXPECT_THROW(io::plan_walls_in_grid(*model, square_room(), gridmap(), options), InputError);
}

}  // namespace
}  // namespace floorgrid
