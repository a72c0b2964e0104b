// `floorgrid simulate` end to end: files, determinism, and other readers of what it writes.
#include <gtest/gtest.h>

#include <filesystem>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/simulation/simulator.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::run_command;
using test::run_floorgrid;
using test::TempDir;

void simulate_to(const std::string& preset, int seed, const fs::path& out) {
  const auto run = run_floorgrid("simulate --preset " + preset + " --seed " + std::to_string(seed) +
                                 " --out " + quoted(out) + " --preview");
  ASSERT_EQ(run.status, 0) << run.err;
}

TEST(SimulateCommand, SameSeedSameBytesOtherSeedOtherBuilding) {
  TempDir dir;
  simulate_to("office", 7, dir / "a");
  simulate_to("office", 7, dir / "b");
  simulate_to("office", 8, dir / "c");
  const std::vector<std::string> files = {"floorplan.dxf",    "gridmap.yaml", "gridmap.pgm",
                                          "log.carmen",       "dataset.yaml", "truth.json",
                                          "manual_pairs.csv", "preview.png"};
  for (const auto& f : files) {
    ASSERT_TRUE(fs::exists(dir / "a" / f)) << f;
    EXPECT_EQ(read_file(dir / "a" / f), read_file(dir / "b" / f)) << f << " differs between runs";
  }
  for (const auto& f : {"floorplan.dxf", "log.carmen", "gridmap.pgm", "truth.json"}) {
    EXPECT_NE(read_file(dir / "a" / f), read_file(dir / "c" / f)) << f << " same for two seeds";
  }
  // Nothing else, and no temporary file left behind.
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(dir / "a")) {
    ++count;
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(count, files.size());
}

TEST(SimulateCommand, WrittenFilesReadBackExactly) {
  TempDir dir;
  simulate_to("office-inches", 3, dir.path());
  const SimulatedDataset d = simulate("office-inches", 3);

  // The log: every pose, range and timestamp as simulated.
  const RobotLog log = io::read_carmen(dir / "log.carmen");
  ASSERT_EQ(log.scans.size(), d.log.scans.size());
  ASSERT_EQ(log.odometry.size(), d.log.odometry.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const LaserScan& a = log.scans[i];
    const LaserScan& b = d.log.scans[i];
    ASSERT_EQ(a.type, "FLASER");
    ASSERT_EQ(a.ranges, b.ranges) << "scan " << i;
    ASSERT_EQ(a.timestamp, b.timestamp);
    ASSERT_EQ(a.robot_pose.x, b.robot_pose.x);
    ASSERT_EQ(a.robot_pose.theta, b.robot_pose.theta);
    ASSERT_EQ(a.laser_pose.y, b.laser_pose.y);
    ASSERT_NEAR(a.angle_increment, b.angle_increment, 1e-15);
    ASSERT_EQ(a.max_range, b.max_range);
  }
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    ASSERT_EQ(log.odometry[i].pose.x, d.log.odometry[i].pose.x);
    ASSERT_EQ(log.odometry[i].timestamp, d.log.odometry[i].timestamp);
  }

  // The plan: inches under a header saying mm, found out by the reader.
  const io::DxfFloorplan dxf = io::read_dxf(dir / "floorplan.dxf");
  EXPECT_EQ(dxf.report.header_units, "mm");
  EXPECT_EQ(dxf.report.units_used, "in");
  EXPECT_FALSE(dxf.report.warnings.empty());
  ASSERT_EQ(dxf.plan.segments().size(), d.plan.segments().size());
  for (std::size_t i = 0; i < d.plan.segments().size(); ++i) {
    ASSERT_LT((dxf.plan.segments()[i].a - d.plan.segments()[i].a).norm(), 1e-9);
  }
  EXPECT_EQ(dxf.plan.arcs().size(), d.plan.arcs().size());

  // The gridmap, the manual pairs and the truth.
  const io::LoadedMap map = io::read_map_yaml(dir / "gridmap.yaml");
  EXPECT_EQ(map.grid.states(), d.gridmap.states());
  EXPECT_EQ(map.grid.geometry().origin.x, d.gridmap.geometry().origin.x);
  const ReferencePairs pairs = io::read_pairs_csv(dir / "manual_pairs.csv");
  EXPECT_EQ(pairs.points_in_grid, d.manual_pairs.points_in_grid);
  const PlanTruth truth = io::read_plan_truth(dir / "truth.json");
  const Eigen::Vector2d p = d.plan.segments()[5].a;
  EXPECT_EQ(truth.plan_to_grid(p), d.truth().plan_to_grid(p));

  // The manifest: scale and units left to be found, both starts given, truth referenced.
  const io::DatasetManifest m = io::read_manifest(dir.path());
  EXPECT_FALSE(m.floorplan_scale.has_value());
  EXPECT_EQ(m.floorplan_units, "auto");
  ASSERT_TRUE(m.initial_pose.has_value());
  EXPECT_EQ(m.initial_pose->grid.x, d.start_in_grid.x);
  EXPECT_TRUE(m.truth.warp.has_value());
  EXPECT_TRUE(m.truth.manual_pairs.has_value());

  // The preview: one pixel per gridmap cell.
  const io::GreyImage preview = io::read_grey_image(dir / "preview.png");
  EXPECT_EQ(preview.width, d.gridmap.width());
  EXPECT_EQ(preview.height, d.gridmap.height());
  EXPECT_EQ(run_floorgrid("info " + quoted(dir.path())).status, 0);
}

TEST(SimulateCommand, WarehousePlanHasRacksAndDoorsOnTheirLayers) {
  TempDir dir;
  simulate_to("warehouse", 1, dir.path());
  const io::DxfFloorplan dxf = io::read_dxf(dir / "floorplan.dxf");
  EXPECT_EQ(dxf.report.units_used, "m");
  EXPECT_GT(dxf.report.entities_by_layer.at("RACKS").at("LINE"), 20u);
  EXPECT_GT(dxf.report.entities_by_layer.at("DOORS").at("ARC"), 2u);
  EXPECT_GT(dxf.report.entities_by_layer.at("WALLS").at("LINE"), 10u);
  EXPECT_NEAR(dxf.plan.bounds().sizes().x(), 100.0, 6.0);
}

TEST(SimulateCommand, MrptCarmen2RawlogConvertsTheLog) {
  if (run_command("command -v carmen2rawlog").status != 0) {
    GTEST_SKIP() << "MRPT's carmen2rawlog is not installed (Debian mrpt-apps): smoke test skipped";
  }
  TempDir dir;
  simulate_to("office", 2, dir.path());
  const auto convert = run_command("carmen2rawlog -q -w -i " + quoted(dir / "log.carmen") + " -o " +
                                   quoted(dir / "log.rawlog"));
  ASSERT_EQ(convert.status, 0) << convert.err;
  const auto info = run_command("rawlog-edit --info -i " + quoted(dir / "log.rawlog"));
  ASSERT_EQ(info.status, 0) << info.err;
  const long scans = std::stol(run_command("grep -c '^FLASER ' " + quoted(dir / "log.carmen")).out);
  EXPECT_NE(info.out.find("FLASER /   " + std::to_string(scans)), std::string::npos) << info.out;
}

TEST(SimulateCommand, BadArgumentsExitWithTwo) {
  TempDir dir;
  const auto preset = run_floorgrid("simulate --preset castle --out " + quoted(dir / "x"));
  EXPECT_EQ(preset.status, 2);
  EXPECT_NE(preset.err.find("castle"), std::string::npos) << preset.err;
  EXPECT_EQ(run_floorgrid("simulate --preset office").status, 2);  // no --out
  test::write_file(dir / "file", "x");
  const auto blocked = run_floorgrid("simulate --out " + quoted(dir / "file" / "sub"));
  EXPECT_EQ(blocked.status, 2);
  EXPECT_NE(blocked.err.find("file"), std::string::npos) << blocked.err;
}

TEST(SimulateCommand, DurationGivesARunOfThatLengthAndBadOnesAreRefusedByName) {
  TempDir dir;
  const auto run = run_floorgrid("simulate --preset office --duration 60 --seed 4 --out " +
                                 quoted(dir / "minute"));
  ASSERT_EQ(run.status, 0) << run.err;
  const RobotLog log = io::read_carmen(dir / "minute" / "log.carmen");
  ASSERT_EQ(log.scans.size(), 901u);  // 15 a second, the first at 0 s and the last at 60 s
  EXPECT_NEAR(log.scans.back().timestamp - log.scans.front().timestamp, 60.0, 1e-3);
  EXPECT_NE(run.out.find("901 scans"), std::string::npos) << run.out;
  for (const std::string bad : {"0", "-5", "nan", "inf", "100000", "abc"}) {
    const auto refused = run_floorgrid("simulate --preset office --duration " + bad + " --out " +
                                       quoted(dir / "bad"));
    EXPECT_EQ(refused.status, 2) << bad;
    EXPECT_NE(refused.err.find("--duration"), std::string::npos) << bad << ": " << refused.err;
    EXPECT_FALSE(fs::exists(dir / "bad")) << bad;
  }
  // Only with a preset.
  EXPECT_EQ(
      run_floorgrid("simulate --from-log x.log --duration 60 --out " + quoted(dir / "c")).status,
      2);
}

TEST(SimulateCommand, FromARealLogWritesADatasetOtherToolsRead) {
  FLOORGRID_REQUIRE_DATA("carmen/aces-corrected.log.gz");
  TempDir dir;
  const std::string log = quoted(test::data_path("carmen/aces-corrected.log.gz"));
  const auto png = run_floorgrid("simulate --from-log " + log +
                                 " --seed 4 --plan-scale 1.7 --rotation 30 --bend 0.5 --out " +
                                 quoted(dir / "png") + " --preview");
  ASSERT_EQ(png.status, 0) << png.err;
  for (const auto* f :
       {"floorplan.yaml", "floorplan.png", "gridmap.yaml", "gridmap.pgm", "log.carmen",
        "manual_pairs.csv", "truth.json", "dataset.yaml", "preview.png"}) {
    EXPECT_TRUE(fs::exists(dir / "png" / f)) << f;
  }
  // The manifest gives no start and no scale; the truth holds the scale asked for.
  const io::DatasetManifest m = io::read_manifest(dir / "png");
  EXPECT_FALSE(m.initial_pose);
  EXPECT_FALSE(m.floorplan_scale);
  ASSERT_TRUE(m.odometry_noise);
  const PlanTruth truth = io::read_plan_truth(dir / "png" / "truth.json");
  EXPECT_NEAR(truth.plan_scale(), 1.0 / 1.7, 1e-12);
  // The plan's map YAML says its (wrong) resolution: true pixel 0.05 m, times 1 / 1.7.
  const io::LoadedMap plan = io::read_map_yaml(dir / "png" / "floorplan.yaml");
  EXPECT_NEAR(plan.grid.resolution(), 0.05 / 1.7, 1e-12);
  // The log written is the log read: poses and readings exact.
  const io::CarmenLog original =
      io::read_carmen_log(test::data_path("carmen/aces-corrected.log.gz"));
  const io::CarmenLog written = io::read_carmen_log(dir / "png" / "log.carmen");
  ASSERT_EQ(written.scans.size(), original.scans.size());
  for (std::size_t i = 0; i < written.scans.size(); i += 37) {
    EXPECT_EQ(written.scans[i].robot_pose.x, original.scans[i].robot_pose.x);
    EXPECT_EQ(written.scans[i].ranges, original.scans[i].ranges);
  }
  EXPECT_EQ(run_floorgrid("info " + quoted(dir / "png")).status, 0);

  const auto dxf = run_floorgrid("simulate --from-log " + log +
                                 " --seed 4 --plan-format dxf --dxf-units mm --dxf-header none "
                                 "--out " +
                                 quoted(dir / "dxf"));
  ASSERT_EQ(dxf.status, 0) << dxf.err;
  // In mm without a header: read as mm, the drawing is the building's size in plan metres.
  io::DxfReadOptions mm;
  mm.units = "mm";
  const io::DxfFloorplan read = io::read_dxf(dir / "dxf" / "floorplan.dxf", mm);
  EXPECT_GT(read.plan.segments().size(), 100u);
  EXPECT_EQ(read.report.header_units, "none");
  // ACES is about 60 m across: read as mm, the plan is that in world metres (in metres it
  // would be 60 km, in cm 6 km).
  const PlanTruth dxf_truth = io::read_plan_truth(dir / "dxf" / "truth.json");
  const double width = read.plan.bounds().sizes().maxCoeff() / dxf_truth.plan_scale();
  EXPECT_GT(width, 40.0);
  EXPECT_LT(width, 120.0);
  // In cm without a header, at scale 1 (seed 3): the drawing guesses inches (67% against 15%
  // for cm: ACES has no door swings). Loaded with the manifest's floorplan_units auto, the run
  // decides between the plausible units by registering the gridmap on the plan near scale 1:
  // it overrules the drawing, and the plan is the cm drawing, at the building's true size.
  const auto cm = run_floorgrid("simulate --from-log " + log +
                                " --seed 3 --plan-format dxf --dxf-units cm --dxf-header none "
                                "--plan-scale 1 --out " +
                                quoted(dir / "cm"));
  ASSERT_EQ(cm.status, 0) << cm.err;
  const io::LoadedDataset loaded = io::load_dataset(dir / "cm");
  ASSERT_TRUE(loaded.dxf_report && loaded.unit_decision);
  EXPECT_NE(loaded.unit_decision->drawn, PlanUnit::cm) << "the drawing guessed right: no test";
  EXPECT_TRUE(loaded.unit_decision->overruled()) << loaded.unit_decision->reason;
  EXPECT_EQ(loaded.dxf_report->units_used, "cm") << loaded.unit_decision->reason;
  EXPECT_DOUBLE_EQ(loaded.dxf_report->metres_per_unit, 0.01);
  io::DxfReadOptions in_cm;
  in_cm.units = "cm";
  EXPECT_TRUE(loaded.plan->bounds().isApprox(
      io::read_dxf(dir / "cm" / "floorplan.dxf", in_cm).plan.bounds(), 1e-6));
}

TEST(SimulateCommand, FromLogOptionsAreCheckedBeforeAnyWork) {
  TempDir dir;
  // Log options without a log, a preset with a log, a bad scale, a missing log.
  EXPECT_EQ(run_floorgrid("simulate --plan-scale 2 --out " + quoted(dir / "a")).status, 2);
  EXPECT_EQ(
      run_floorgrid("simulate --preset office --from-log x.log --out " + quoted(dir / "a")).status,
      2);
  test::write_file(dir / "tiny.log", "FLASER 3 1 1 1 0 0 0 0 0 0 1 h 1\n");
  const auto scale = run_floorgrid("simulate --from-log " + quoted(dir / "tiny.log") +
                                   " --plan-scale -3 --out " + quoted(dir / "b"));
  EXPECT_EQ(scale.status, 2);
  EXPECT_NE(scale.err.find("--plan-scale"), std::string::npos) << scale.err;
  EXPECT_FALSE(fs::exists(dir / "b"));
  const auto missing = run_floorgrid("simulate --from-log " + quoted(dir / "none.log") + " --out " +
                                     quoted(dir / "c"));
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("none.log"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir / "c"));
}

}  // namespace
}  // namespace floorgrid
