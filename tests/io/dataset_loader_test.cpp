// Loading a dataset bounds what its maps may cost: large maps are cropped to their known area,
// maps too large for the memory limit are refused with the estimate, and a map without free
// space is refused naming its file.
#include "floorgrid/io/dataset/dataset_loader.hpp"

#include <gtest/gtest.h>

#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/plans/dxf_writer.hpp"
#include "floorgrid/maps/layer_filter.hpp"
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

TEST(DatasetLoader, TheRunDecidesUnitsTheDrawingLeavesAmbiguous) {
  // The office's walls alone (no door swings to tell the unit by) in cm, without $INSUNITS: the
  // drawing alone cannot be sure of cm.
  test::TempDir dir;
  std::filesystem::copy(office_dataset(), dir.path(), std::filesystem::copy_options::recursive);
  const io::LoadedDataset metres = io::load_dataset(dir.path());
  io::DxfWriteOptions cm;
  cm.header_units = "none";
  cm.units_per_metre = 100.0;
  io::write_dxf(filter_layers(*metres.plan, {{"WALLS"}, {}}), dir / "floorplan.dxf", cm);
  PlanUnitFitOptions quick;  // the office is small and clear
  quick.registration.candidates = 4;
  quick.registration.max_points = 1500;
  const io::LoadedDataset d = io::load_dataset(dir.path(), {}, {}, quick);
  ASSERT_TRUE(d.dxf_report && d.unit_decision);
  EXPECT_NE(d.dxf_report->units_confidence, "high");
  EXPECT_GE(d.dxf_report->unit_candidates.size(), 2u);
  EXPECT_EQ(d.dxf_report->units_used, "cm") << d.dxf_report->units_reason;
  EXPECT_DOUBLE_EQ(d.dxf_report->metres_per_unit, 0.01);
  // The drawing guessed right here; the run confirms it (the run overruling a wrong guess:
  // PlanUnitFit.TheRunOverrulesADrawingReadInTheWrongUnit).
  EXPECT_TRUE(d.unit_decision->confirmed) << d.dxf_report->units_reason;
  EXPECT_NE(d.dxf_report->units_reason.find("the gridmap confirms"), std::string::npos);
  // The plan is where the metre drawing put it, and so is its grid.
  EXPECT_TRUE(
      d.plan->bounds().isApprox(filter_layers(*metres.plan, {{"WALLS"}, {}}).bounds(), 1e-6));
  EXPECT_NEAR(d.plan_grid.geometry().resolution, metres.plan_grid.geometry().resolution, 1e-12);
  const nlohmann::json units = io::floorplan_units_json(d);
  EXPECT_EQ(units["unit"], "cm");
  EXPECT_TRUE(units["decided_by_run"].get<bool>());
  EXPECT_GT(units["candidates"][0]["fit_score"].get<double>(), 0.5);
  // A unit the manifest names is obeyed: the run is not asked.
  std::string yaml = test::read_file(dir / "dataset.yaml");
  yaml.replace(yaml.find("floorplan_units: auto"), 21, "floorplan_units: cm");
  test::write_file(dir / "dataset.yaml", yaml);
  const io::LoadedDataset asked = io::load_dataset(dir.path());
  EXPECT_FALSE(asked.unit_decision);
  EXPECT_EQ(asked.dxf_report->units_used, "cm");
}

}  // namespace
}  // namespace floorgrid
