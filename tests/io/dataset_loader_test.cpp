// Loading a dataset bounds what its maps may cost: large maps are cropped to their known area,
// maps too large for the memory limit are refused with the estimate, and a map without free
// space is refused naming its file.
#include "floorgrid/io/dataset_loader.hpp"

#include <gtest/gtest.h>

#include "floorgrid/io/map_io.hpp"
#include "floorgrid/io/simulation_writer.hpp"
#include "floorgrid/simulation/simulator.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// The simulated office written once, shared by the tests (read-only).
const std::filesystem::path& office_dataset() {
  static const test::TempDir dir;
  static const bool written = [] {
    io::write_simulated_dataset(simulate("office", 1), dir.path(), false);
    return true;
  }();
  (void)written;
  return dir.path();
}

TEST(DatasetLoader, LargeMapsAreCroppedToTheirKnownAreaKeepingEveryCellInPlace) {
  const io::LoadedDataset full = io::load_dataset(office_dataset());
  io::DatasetLimits limits;
  limits.crop_above_cells = 1000;  // every map counts as large here
  limits.crop_margin = 1.0;
  const io::LoadedDataset cropped = io::load_dataset(office_dataset(), {}, limits);
  EXPECT_LT(cropped.gridmap.geometry().size(), full.gridmap.geometry().size());
  EXPECT_EQ(cropped.gridmap.counts().occupied, full.gridmap.counts().occupied);
  EXPECT_EQ(cropped.gridmap.counts().free, full.gridmap.counts().free);
  const bool warned = std::any_of(cropped.warnings.begin(), cropped.warnings.end(),
                                  [](const std::string& w) { return w.find("cropped") != w.npos; });
  EXPECT_TRUE(warned);
  // A cell of the cropped map lies where the same cell of the full map does.
  int ix = 0, iy = 0;
  const Eigen::Vector2d centre = cropped.gridmap.geometry().cell_center(10, 10);
  ASSERT_TRUE(full.gridmap.geometry().cell_of(centre, ix, iy));
  EXPECT_LT((full.gridmap.geometry().cell_center(ix, iy) - centre).norm(), 1e-9);
  EXPECT_EQ(full.gridmap.state(ix, iy), cropped.gridmap.state(10, 10));
}

TEST(DatasetLoader, MapsBeyondTheMemoryLimitAreRefusedWithTheEstimate) {
  io::DatasetLimits limits;
  limits.memory_gb = 0.01;
  test::expect_input_error(
      [&] { io::load_dataset(office_dataset(), {}, limits); },
      {"dataset.yaml", "'gridmap'", "GiB to localize in", "more than the limit of 0.0 GiB"});
}

TEST(DatasetLoader, AGridmapWithoutFreeSpaceIsRefusedNamingIt) {
  test::TempDir dir;
  std::filesystem::copy(office_dataset(), dir.path(), std::filesystem::copy_options::recursive);
  // The same gridmap, every cell occupied.
  io::LoadedMap map = io::read_map_yaml(dir / "gridmap.yaml");
  for (int iy = 0; iy < map.grid.height(); ++iy)
    for (int ix = 0; ix < map.grid.width(); ++ix)
      map.grid.set_state(ix, iy, CellState::occupied);
  io::write_map(map.grid, dir / "gridmap.yaml");
  test::expect_input_error([&] { io::load_dataset(dir.path()); },
                           {"gridmap.yaml", "'gridmap'", "no free cell"});
}

TEST(DatasetLoader, AGridmapWhoseThresholdsFindNoWallIsRefusedWithTheValuesAndThresholds) {
  test::TempDir dir;
  std::filesystem::copy(office_dataset(), dir.path(), std::filesystem::copy_options::recursive);
  // A SLAM map whose walls are grey 100 (occupancy 0.608), saved with occupied_thresh 0.65: the
  // rule finds no wall at all.
  const io::LoadedMap map = io::read_map_yaml(dir / "gridmap.yaml");
  const GridGeometry& g = map.grid.geometry();
  std::vector<std::uint8_t> pixels(g.size());
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const CellState state = map.grid.state(ix, iy);
      pixels[static_cast<std::size_t>(g.image_row(iy)) * g.width + ix] =
          state == CellState::occupied ? 100
          : state == CellState::free   ? 254
                                       : 205;
    }
  }
  io::write_pgm(dir / "gridmap.pgm", g.width, g.height, pixels);
  test::expect_input_error(
      [&] { io::load_dataset(dir.path()); },
      {"gridmap.yaml", "'gridmap'", "finds 0 occupied cells", "darkest pixel has occupancy 0.608",
       "occupied_thresh 0.65", "not the resolution or origin"});
  // With the threshold below the walls' grey, the same map loads.
  std::string yaml = test::read_file(dir / "gridmap.yaml");
  yaml.replace(yaml.find("occupied_thresh: 0.65"), 21, "occupied_thresh: 0.55");
  test::write_file(dir / "gridmap.yaml", yaml);
  EXPECT_NO_THROW(io::load_dataset(dir.path()));
}

}  // namespace
}  // namespace floorgrid
