// `floorgrid simulate --from-plan` end to end: the files a dataset holds and what reads them,
// determinism, bad input, and a real drawing.
#include <gtest/gtest.h>

#include <filesystem>

#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::read_json;
using test::run_floorgrid;
using test::TempDir;

// A drawing as a map YAML: two rooms in a 10 x 6 m outline at 0.05 m per pixel, a partition
// with a 0.9 m door. With `walls` false, blank paper.
fs::path write_drawing(const fs::path& folder, bool walls = true) {
  GridGeometry g;
  g.width = 280;
  g.height = 200;
  g.resolution = 0.05;
  g.origin = {-3.0, 2.0, 0.0};
  OccupancyGrid grid(g, CellState::free);
  const auto draw = [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x)
        grid.set_state(x, y, CellState::occupied);
    }
  };
  if (walls) {
    draw(40, 40, 240, 41);    // bottom
    draw(40, 159, 240, 160);  // top
    draw(40, 40, 41, 160);    // left
    draw(239, 40, 240, 160);  // right
    draw(140, 40, 141, 91);   // the partition, a door from y 92 to 109
    draw(140, 110, 141, 160);
  }
  const fs::path yaml = folder / "drawing.yaml";
  io::write_map(grid, yaml);
  return yaml;
}

TEST(SimulateFromPlan, WritesADatasetEveryReaderTakes) {
  TempDir dir;
  const fs::path drawing = write_drawing(dir.path());
  const auto run =
      run_floorgrid("simulate --from-plan " + quoted(drawing) +
                    " --seed 2 --plan-scale 1.5 --out " + quoted(dir / "a") + " --preview");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("furniture"), std::string::npos) << run.out;
  for (const auto* f :
       {"floorplan.yaml", "floorplan.pgm", "gridmap.yaml", "gridmap.pgm", "log.carmen",
        "manual_pairs.csv", "truth.json", "dataset.yaml", "preview.png", "world.png"}) {
    EXPECT_TRUE(fs::exists(dir / "a" / f)) << f;
  }
  // The plan is the drawing as given, its resolution and origin carrying the scale error.
  EXPECT_EQ(read_file(dir / "a" / "floorplan.pgm"), read_file(dir / "drawing.pgm"));
  const io::LoadedMap plan = io::read_map_yaml(dir / "a" / "floorplan.yaml");
  EXPECT_NEAR(plan.grid.resolution(), 0.05 / 1.5, 1e-12);
  EXPECT_NEAR(plan.grid.geometry().origin.x, -3.0 / 1.5, 1e-12);
  // The manifest leaves the start and the scale to be found and names the truth.
  const io::DatasetManifest m = io::read_manifest(dir / "a");
  EXPECT_FALSE(m.initial_pose.has_value());
  EXPECT_FALSE(m.floorplan_scale.has_value());
  EXPECT_FALSE(m.odometry_noise.has_value());  // the log's odometry is noisy already
  ASSERT_TRUE(m.truth.warp.has_value());
  const PlanTruth truth = io::read_plan_truth(*m.truth.warp);
  EXPECT_DOUBLE_EQ(truth.plan_scale(), 1.0 / 1.5);
  const auto t = read_json(dir / "a" / "truth.json");
  EXPECT_EQ(t["preset"], "from-plan");
  EXPECT_GT(t["statistics"]["scans"].get<int>(), 50);
  EXPECT_GT(t["statistics"]["warp_fit_scale"].get<double>(), 0.9);
  // A CARMEN log with odometry and laser lines.
  const RobotLog log = io::read_carmen(dir / "a" / "log.carmen");
  EXPECT_EQ(log.scans.size(), t["statistics"]["scans"].get<std::size_t>());
  EXPECT_GT(log.odometry.size(), log.scans.size());
  EXPECT_EQ(run_floorgrid("info " + quoted(dir / "a")).status, 0);
  // The same seed again: the same bytes.
  ASSERT_EQ(run_floorgrid("simulate --from-plan " + quoted(drawing) +
                          " --seed 2 --plan-scale 1.5 --out " + quoted(dir / "b"))
                .status,
            0);
  for (const auto* f : {"log.carmen", "gridmap.pgm", "truth.json", "manual_pairs.csv"})
    EXPECT_EQ(read_file(dir / "a" / f), read_file(dir / "b" / f)) << f;
}

TEST(SimulateFromPlan, BadInputExitsTwoNamingTheOptionOrFile) {
  TempDir dir;
  const fs::path drawing = write_drawing(dir.path());
  const auto expect_refused = [&](const std::string& args, const std::string& named) {
    const auto run = run_floorgrid("simulate " + args + " --out " + quoted(dir / "out"));
    EXPECT_EQ(run.status, 2) << args << "\n" << run.err;
    EXPECT_NE(run.err.find(named), std::string::npos) << args << "\n" << run.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << args;  // nothing left behind
  };
  const fs::path image = dir / "drawing.pgm";
  expect_refused("--from-plan " + quoted(image), "--resolution");
  expect_refused("--from-plan " + quoted(drawing) + " --resolution 0.05", "--resolution");
  expect_refused("--from-plan " + quoted(dir / "missing.png"), "--from-plan");
  test::write_file(dir / "notes.txt", "walls\n");
  expect_refused("--from-plan " + quoted(dir / "notes.txt"), "notes.txt");
  expect_refused("--from-plan " + quoted(drawing) + " --drawing-errors many", "--drawing-errors");
  expect_refused("--from-plan " + quoted(drawing) + " --plan-scale 0", "--plan-scale");
  expect_refused("--from-plan " + quoted(drawing) + " --bend -1", "--bend");
  expect_refused("--preset office --plan-scale 2", "--plan-scale");
  expect_refused("--from-plan " + quoted(image) + " --resolution 0.05 --origin 1,x", "--origin");
  TempDir blank;
  const fs::path paper = write_drawing(blank.path(), false);
  expect_refused("--from-plan " + quoted(paper), "no walls");
}

TEST(SimulateFromPlan, BuildsAWorldFromFreiburg079sDrawing) {
  FLOORGRID_REQUIRE_DATA("fr079/floorplan.png");
  TempDir dir;
  const auto run =
      run_floorgrid("simulate --from-plan " + quoted(test::data_path("fr079/floorplan.png")) +
                    " --resolution 0.05 --seed 1 --drawing-errors some --out " + quoted(dir / "d"));
  ASSERT_EQ(run.status, 0) << run.err;
  const auto t = read_json(dir / "d" / "truth.json");
  const auto& s = t["statistics"];
  EXPECT_GE(s["regions"].get<int>(), 15);  // the drawing's 16 rooms and its corridor
  EXPECT_GE(s["regions_visited"].get<int>(), 10);
  EXPECT_GE(s["doors_open"].get<int>(), 5);
  EXPECT_GE(s["drawing_errors"].get<int>(), 2);
  EXPECT_GE(s["furniture_fraction"].get<double>(), 0.2);  // as the presets
  EXPECT_GT(s["scans"].get<int>(), 500);
  EXPECT_EQ(run_floorgrid("info " + quoted(dir / "d")).status, 0);
}

}  // namespace
}  // namespace floorgrid
