// End-to-end tests of `floorgrid info`: the built binary on real and made-up files.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

using nlohmann::json;
using test::data_path;
using test::quoted;
using test::run_command;
using test::run_floorgrid;

json info_json(const std::filesystem::path& path, const std::string& extra = "") {
  const auto run = run_floorgrid("info --json " + quoted(path) + " " + extra);
  EXPECT_EQ(run.status, 0) << run.err;
  return json::parse(run.out);
}

long count_lines(const std::string& command) {
  return std::stol(run_command(command).out);
}

TEST(InfoCommand, BonnGMapSizeAndBounds) {
  FLOORGRID_REQUIRE_DATA("bonn/GMap/GMap.yaml");
  const auto path = data_path("bonn/GMap/GMap.yaml");
  const auto text = run_floorgrid("info " + quoted(path));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("604 x 272 cells at 0.05 m"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("x -13.903 .. 16.297 m, y -10.828 .. 2.772 m"), std::string::npos)
      << text.out;
  const json j = info_json(path);
  EXPECT_EQ(j["kind"], "map");
  EXPECT_EQ(j["width"], 604);
  EXPECT_EQ(j["cells"]["occupied"].get<long>() + j["cells"]["free"].get<long>() +
                j["cells"]["unknown"].get<long>(),
            604 * 272);
}

TEST(InfoCommand, RealLogsReportScansBeamsAndIncrement) {
  struct Case {
    const char* file;
    long beams;
    double increment_deg;
  };
  for (const Case& c : {Case{"fr079/freiburg-079-corrected.log.gz", 360, 0.5},
                        Case{"carmen/aces-corrected.log.gz", 180, 1.0},
                        Case{"carmen/csail-corrected.log.gz", 361, 0.5}}) {
    if (!std::filesystem::exists(data_path(c.file))) {
      GTEST_SKIP() << "shared data missing: " << data_path(c.file);
    }
    const auto path = data_path(c.file);
    const long flaser = count_lines("zcat " + quoted(path) + " | grep -c '^FLASER '");
    const json j = info_json(path);
    EXPECT_EQ(j["kind"], "log");
    EXPECT_EQ(j["laser_scans"].get<long>(), flaser) << c.file;
    ASSERT_EQ(j["lasers"].size(), 1u) << c.file;
    EXPECT_EQ(j["lasers"][0]["beams"].get<long>(), c.beams) << c.file;
    EXPECT_NEAR(j["lasers"][0]["angle_increment_deg"]["value"].get<double>(), c.increment_deg, 1e-9)
        << c.file;
    EXPECT_EQ(j["messages"]["FLASER"]["lines"].get<long>(), flaser);
    EXPECT_EQ(j["messages"]["ODOM"]["lines"].get<long>(),
              count_lines("zcat " + quoted(path) + " | grep -c '^ODOM '"));
    EXPECT_GT(j["duration_s"].get<double>(), 0.0);
  }
  const auto fr079 =
      run_floorgrid("info " + quoted(data_path("fr079/freiburg-079-corrected.log.gz")));
  EXPECT_NE(fr079.out.find("4791 laser scans"), std::string::npos) << fr079.out;
  EXPECT_NE(fr079.out.find("360 beams at 0.5 deg"), std::string::npos) << fr079.out;
}

TEST(InfoCommand, DxfUnitsExtentAndBinaryRefusal) {
  FLOORGRID_REQUIRE_DATA("dxf/house_floorplan_r2004.dxf");
  const json house = info_json(data_path("dxf/house_floorplan_r2004.dxf"));
  EXPECT_EQ(house["header_units"], "mm");
  EXPECT_EQ(house["units_used"], "in");
  ASSERT_FALSE(house["warnings"].empty());
  EXPECT_NE(house["warnings"][0].get<std::string>().find("$INSUNITS says mm"), std::string::npos);
  // The saved $EXTMIN/$EXTMAX (annotation included) span about 24 x 24 m in inches.
  EXPECT_NEAR(house["header_extent_m"]["size"][0].get<double>(), 24.5, 0.5);
  EXPECT_NEAR(house["header_extent_m"]["size"][1].get<double>(), 23.8, 0.5);
  EXPECT_GT(house["entities_by_type"]["LINE"].get<int>(), 100);
  EXPECT_GT(house["annotation_skipped"]["TEXT"].get<int>(), 0);
  // Which units, from what evidence, how sure, and the candidates.
  EXPECT_EQ(house["units_source"], "header_overruled");
  EXPECT_EQ(house["units_confidence"], "high");
  ASSERT_GE(house["units_evidence"].size(), 4u);
  EXPECT_NE(house["units_evidence"].dump().find("63 dimension texts"), std::string::npos);
  ASSERT_FALSE(house["unit_candidates"].empty());
  EXPECT_EQ(house["unit_candidates"][0]["unit"], "in");
  EXPECT_EQ(house["unit_candidates"][0]["metres_per_unit"], 0.0254);
  EXPECT_GT(house["unit_candidates"][0]["probability"].get<double>(), 0.999);
  const auto text = run_floorgrid("info " + quoted(data_path("dxf/house_floorplan_r2004.dxf")));
  EXPECT_NE(text.out.find("from the drawing, overruling $INSUNITS, confidence high"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("evidence  10 door swings"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("candidates  in 100%"), std::string::npos) << text.out;

  const json site = info_json(data_path("dxf/house_site_r2000.dxf"));
  EXPECT_EQ(site["units_used"], "m");
  EXPECT_EQ(site["units_source"], "header");
  EXPECT_NEAR(site["extent_m"]["size"][0].get<double>(), 43.0, 1.0);
  EXPECT_NEAR(site["extent_m"]["size"][1].get<double>(), 33.0, 1.0);

  const json r12 = info_json(data_path("dxf/sample_r12_ascii.dxf"));
  EXPECT_GT(r12["entities_by_type"]["POLYLINE"].get<int>(), 0);
  EXPECT_EQ(r12["units_source"], "guessed");
  EXPECT_NE(r12["units_confidence"], "high");

  const auto binary = run_floorgrid("info " + quoted(data_path("dxf/sample_r2018_binary.dxf")));
  EXPECT_EQ(binary.status, 2);
  EXPECT_NE(binary.err.find("binary DXF is not supported"), std::string::npos) << binary.err;
  EXPECT_NE(binary.err.find("sample_r2018_binary.dxf"), std::string::npos) << binary.err;
}

TEST(InfoCommand, BareImageAndDataset) {
  FLOORGRID_REQUIRE_DATA("fr079/slam_map.png");
  const json pixels = info_json(data_path("fr079/slam_map.png"));
  EXPECT_EQ(pixels["kind"], "image");
  EXPECT_FALSE(pixels.contains("bounds_m"));
  const json metric =
      info_json(data_path("fr079/slam_map.png"), "--resolution 0.05 --origin -1,-2,0");
  EXPECT_NEAR(metric["bounds_m"]["max"][0].get<double>(), -1.0 + 700 * 0.05, 1e-9);

  test::TempDir dir;
  test::write_file(
      dir / "dataset.yaml",
      "name: fr079\nfloorplan: " + data_path("fr079/floorplan.png").string() +
          "\nfloorplan_resolution: 0.05\ngridmap: " + data_path("fr079/slam_map.png").string() +
          "\ngridmap_resolution: 0.05\nlog: " +
          data_path("fr079/freiburg-079-corrected.log.gz").string() +
          "\nfloorplan_scale: auto\nodometry_noise: [0.05, 0.01, 0.02, 0.05]\n");
  const json dataset = info_json(dir.path());
  EXPECT_EQ(dataset["kind"], "dataset");
  EXPECT_EQ(dataset["floorplan"]["width"], 800);
  EXPECT_EQ(dataset["gridmap"]["width"], 700);
  EXPECT_EQ(dataset["log"]["laser_scans"], 4791);
  EXPECT_EQ(dataset["floorplan_scale"], "auto");
}

TEST(InfoCommand, BadInputExitsWithTwoAndNamesTheFile) {
  test::TempDir dir;
  test::write_file(dir / "mystery.bin", "\x01\x02\x03 nothing we know");
  test::write_file(dir / "bad.yaml",
                   "image: m.pgm\nresolution: fast\norigin: [0,0,0]\n"
                   "occupied_thresh: 0.65\nfree_thresh: 0.2\n");
  test::write_file(dir / "dataset.yaml", "floorplan: a.dxf\ngridmap: b.yaml\nsurprise: 1\n");
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {quoted(dir / "nothere.yaml"), "nothere.yaml"},
           {quoted(dir / "mystery.bin"), "cannot tell"},
           {quoted(dir / "bad.yaml"), "'resolution'"},
           {quoted(dir.path()), "'surprise'"},
           {quoted(dir / "bad.yaml") + " --origin 1,x", "--origin"}}) {
    const auto run = run_floorgrid("info " + args);
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_NE(run.err.find(expected), std::string::npos) << args << ": " << run.err;
  }
  const auto usage = run_floorgrid("info");
  EXPECT_EQ(usage.status, 2);
}

}  // namespace
}  // namespace floorgrid
