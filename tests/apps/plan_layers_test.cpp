// `floorgrid export --format nav2-keepout|nav2-speed|nav2-waypoints|geojson` and `floorgrid
// migrate` end to end on simulated offices (exact truth): waypoints carried to the gridmap
// against the truth per waypoint, the mask on the gridmap's grid, and bad input (exit 2, a
// message naming the file and the feature, no output left).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/maps/polygon_raster.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::run_floorgrid;
using test::TempDir;
using test::write_file;

/// A simulated preset in dir/data and a gp model with std_m fitted on its emulated hand-picked
/// pairs (`fit --cv 5`), dir/model.json: old map = the plan, new map = the gridmap.
void prepare(const TempDir& dir, const std::string& preset) {
  const auto sim = run_floorgrid(
      fmt::format("simulate --preset {} --seed 1 --out {}", preset, quoted(dir / "data")));
  ASSERT_EQ(sim.status, 0) << sim.err;
  const auto fit = run_floorgrid("fit --pairs " + quoted(dir / "data" / "manual_pairs.csv") +
                                 " --model gp --cv 5 --out " + quoted(dir / "model.json"));
  ASSERT_EQ(fit.status, 0) << fit.err;
}

/// Waypoints inside the office (plan metres), a heading each, and one far outside.
const char* kWaypoints =
    "name,x,y,theta\n"
    "dock,6.5,4.0,0.0\n"
    "printer,12.0,6.0,1.57\n"
    "lab door,20.5,12.0,3.1\n"
    "station a,30.0,15.0,-1.2\n"
    "store,35.0,5.0,0.7\n"
    "far away,80.0,60.0,\n";

void migrate_waypoints_against_truth(const std::string& preset) {
  TempDir dir;
  prepare(dir, preset);
  write_file(dir / "waypoints.csv", kWaypoints);
  const auto run = run_floorgrid("migrate --model " + quoted(dir / "model.json") + " " +
                                 quoted(dir / "waypoints.csv") + " --out " + quoted(dir / "new"));
  ASSERT_EQ(run.status, 0) << run.err;
  const PlanTruth truth = io::read_plan_truth(dir / "data" / "truth.json");
  const std::string csv = read_file(dir / "new" / "waypoints.csv");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  ASSERT_EQ(line, "name,x,y,theta,std_m,nearest_pair_m,flag,extrapolated");
  std::istringstream given(kWaypoints);
  std::getline(given, line);
  int rows = 0;
  while (std::getline(lines, line)) {
    std::string in;
    ASSERT_TRUE(std::getline(given, in));
    std::vector<std::string> f, g;
    std::stringstream a(line), b(in);
    for (std::string s; std::getline(a, s, ',');)
      f.push_back(s);
    for (std::string s; std::getline(b, s, ',');)
      g.push_back(s);
    ASSERT_GE(f.size(), 8u) << line;
    ASSERT_EQ(f[0], g[0]) << "rows in input order, none dropped";
    const Eigen::Vector2d plan(std::stod(g[1]), std::stod(g[2]));
    const Eigen::Vector2d moved(std::stod(f[1]), std::stod(f[2]));
    const double error = (moved - truth.plan_to_grid(plan)).norm();
    const double std_m = std::stod(f[4]);
    std::printf("%s %-10s error %.3f m, std_m %.3f, flag %s\n", preset.c_str(), f[0].c_str(), error,
                std_m, f[6].c_str());
    if (f[0] == "far away") {
      EXPECT_EQ(f[7], "1") << "flagged extrapolated, kept";
      EXPECT_EQ(f[6], "outside_hull");
      continue;
    }
    // Inside the building: within nav2's default goal tolerance, and within 3 std_m.
    EXPECT_LT(error, 0.25) << f[0];
    EXPECT_LT(error, 3.0 * std_m) << f[0];
    // The heading: the truth's turn of the plan heading at the point.
    const Pose2 expected = truth.pose_plan_to_grid({plan.x(), plan.y(), std::stod(g[3])});
    EXPECT_LT(std::abs(normalize_angle(std::stod(f[3]) - expected.theta)), 0.02) << f[0];
    ++rows;
  }
  EXPECT_EQ(rows, 5);
}

TEST(PlanLayersCommand, MigratedWaypointsLieWhereTheTruthPutsThemOffice) {
  migrate_waypoints_against_truth("office");
}

TEST(PlanLayersCommand, MigratedWaypointsLieWhereTheTruthPutsThemBentOffice) {
  migrate_waypoints_against_truth("bent-office");
}

const char* kZones = R"({"type": "FeatureCollection", "features": [
 {"type": "Feature", "properties": {"name": "loading bay"}, "geometry": {"type": "Polygon",
  "coordinates": [[[5, 3], [10, 3], [10, 8], [5, 8], [5, 3]]]}},
 {"type": "Feature", "properties": {"name": "dock", "theta": 1.57}, "geometry":
  {"type": "Point", "coordinates": [12, 6]}}]})";

TEST(PlanLayersCommand, ExportsAKeepoutMaskOnTheGridmapsGridWaypointsAndGeoJson) {
  TempDir dir;
  prepare(dir, "office");
  write_file(dir / "zones.geojson", kZones);
  write_file(dir / "waypoints.csv", kWaypoints);
  const std::string common =
      "export --model " + quoted(dir / "model.json") + " --dataset " + quoted(dir / "data");
  const auto keepout =
      run_floorgrid(common + " --format nav2-keepout --zones " + quoted(dir / "zones.geojson") +
                    " --out " + quoted(dir / "keepout.yaml"));
  ASSERT_EQ(keepout.status, 0) << keepout.err;
  const io::LoadedMap gridmap = io::read_map_yaml(dir / "data" / "gridmap.yaml");
  const io::LoadedMap mask = io::read_map_yaml(dir / "keepout.yaml");
  EXPECT_EQ(mask.grid.width(), gridmap.grid.width());
  EXPECT_EQ(mask.grid.height(), gridmap.grid.height());
  EXPECT_EQ(mask.grid.resolution(), gridmap.grid.resolution());
  EXPECT_EQ(mask.grid.geometry().origin.x, gridmap.grid.geometry().origin.x);
  EXPECT_EQ(mask.grid.geometry().origin.y, gridmap.grid.geometry().origin.y);
  // 5 m x 5 m of 5 cm cells, widened by 2 std_m.
  EXPECT_GT(mask.grid.counts().occupied, 9500u);
  EXPECT_LT(mask.grid.counts().occupied, 13000u);
  EXPECT_TRUE(fs::exists(dir / "keepout_filter_info.yaml"));

  const auto waypoints = run_floorgrid(
      "export --model " + quoted(dir / "model.json") + " --format nav2-waypoints --waypoints " +
      quoted(dir / "waypoints.csv") + " --out " + quoted(dir / "waypoints.yaml"));
  ASSERT_EQ(waypoints.status, 0) << waypoints.err;
  const std::string yaml = read_file(dir / "waypoints.yaml");
  std::size_t poses = 0;
  for (std::size_t at = yaml.find("  - header:"); at != std::string::npos;
       at = yaml.find("  - header:", at + 1))
    ++poses;
  EXPECT_EQ(poses, 6u) << yaml;
  EXPECT_NE(yaml.find("# far away: "), std::string::npos) << "kept, flagged";

  const auto geojson =
      run_floorgrid(common + " --format geojson --zones " + quoted(dir / "zones.geojson") +
                    " --out " + quoted(dir / "layers.geojson"));
  ASSERT_EQ(geojson.status, 0) << geojson.err;
  const auto j = nlohmann::json::parse(read_file(dir / "layers.geojson"));
  ASSERT_EQ(j["features"].size(), 2u);
  for (const auto& f : j["features"]) {
    EXPECT_TRUE(f["properties"]["std_m"].is_number()) << f.dump();
    EXPECT_TRUE(f["properties"]["extrapolated"].is_boolean()) << f.dump();
  }
  EXPECT_EQ(j["features"][1]["geometry"]["type"], "Point");
  // The same zone as a mask on "the old map" (the plan's frame: 0.05 m cells from (0, 0)),
  // carried by migrate onto the gridmap's grid: the export's cells again (both widened by K
  // std_m, one at boundary points, the other at boundary cells).
  GridGeometry plan_grid;
  plan_grid.width = 800;
  plan_grid.height = 440;
  plan_grid.resolution = 0.05;
  Eigen::Matrix2Xd square(2, 4);
  square << 5, 10, 10, 5, 3, 3, 8, 8;
  const CellMask zone = rasterize_rings({square}, plan_grid);
  OccupancyGrid old_mask(plan_grid, CellState::free);
  for (int iy = 0; iy < plan_grid.height; ++iy)
    for (int ix = 0; ix < plan_grid.width; ++ix)
      if (zone.at(ix, iy))
        old_mask.set_state(ix, iy, CellState::occupied);
  io::MapWriteOptions trinary;
  trinary.free_thresh = 0.196;
  io::write_map(old_mask, dir / "old_keepout.yaml", trinary);
  const auto migrated = run_floorgrid(
      "migrate --model " + quoted(dir / "model.json") + " " + quoted(dir / "old_keepout.yaml") +
      " --gridmap " + quoted(dir / "data" / "gridmap.yaml") + " --out " + quoted(dir / "new"));
  ASSERT_EQ(migrated.status, 0) << migrated.err;
  const io::LoadedMap moved = io::read_map_yaml(dir / "new" / "old_keepout.yaml");
  EXPECT_EQ(moved.grid.width(), gridmap.grid.width());
  EXPECT_EQ(moved.grid.geometry().origin.x, gridmap.grid.geometry().origin.x);
  EXPECT_EQ(moved.metadata.mode, io::MapMode::trinary);
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < moved.grid.states().size(); ++i) {
    const bool a = moved.grid.states()[i] == CellState::occupied;
    const bool b = mask.grid.states()[i] == CellState::occupied;
    both += a && b;
    either += a || b;
  }
  std::printf("migrated mask against the exported one: IoU %.4f (%zu cells)\n",
              static_cast<double>(both) / static_cast<double>(either), either);
  EXPECT_GT(static_cast<double>(both) / static_cast<double>(either), 0.9)
      << both << " of " << either;
  const auto help = run_floorgrid("export --help");
  for (const char* format : {"nav2-keepout", "nav2-speed", "nav2-waypoints", "geojson"})
    EXPECT_NE(help.out.find(format), std::string::npos) << format;
}

TEST(PlanLayersCommand, BadInputExitsTwoNamingTheFeatureAndLeavesNoFile) {
  TempDir dir;
  prepare(dir, "office");
  const std::string common = "export --model " + quoted(dir / "model.json") + " --dataset " +
                             quoted(dir / "data") + " --format nav2-keepout --out " +
                             quoted(dir / "out" / "keepout.yaml") + " --zones ";
  fs::create_directories(dir / "out");
  const auto bad = [&](const std::string& name, const std::string& text,
                       const std::vector<std::string>& says) {
    write_file(dir / name, text);
    const auto run = run_floorgrid(common + quoted(dir / name));
    EXPECT_EQ(run.status, 2) << name << ": " << run.err;
    for (const std::string& s : says)
      EXPECT_NE(run.err.find(s), std::string::npos) << name << ": '" << s << "' not in " << run.err;
    EXPECT_TRUE(fs::is_empty(dir / "out")) << name << " left a file";
  };
  bad("bow.geojson",
      R"({"type": "Feature", "properties": {"name": "bow tie"}, "geometry": {"type": "Polygon",
          "coordinates": [[[5, 5], [7, 7], [7, 5], [5, 7], [5, 5]]]}})",
      {"bow.geojson", "zone 0 'bow tie': self-intersecting"});
  bad("open.geojson",
      R"({"type": "Feature", "properties": {"name": "bay"}, "geometry": {"type": "Polygon",
          "coordinates": [[[5, 5], [7, 5], [7, 7], [5, 7]]]}})",
      {"open.geojson", "feature 0 'bay'", "open"});
  bad("far.geojson",
      R"({"type": "Feature", "properties": {"name": "moon"}, "geometry": {"type": "Polygon",
          "coordinates": [[[5000, 5000], [5010, 5000], [5010, 5010], [5000, 5000]]]}})",
      {"far.geojson", "zone 0 'moon' lies wholly off the gridmap"});
  bad("wgs84.geojson",
      R"({"type": "Polygon", "coordinates": [[[12.8761, 56.6631], [12.8771, 56.6631],
          [12.8771, 56.6636], [12.8761, 56.6631]]]})",
      {"wgs84.geojson", "plan metres only"});
  const auto nan = [&] {
    write_file(dir / "nan.csv", "name,x,y\ndock,nan,3\n");
    return run_floorgrid("migrate --model " + quoted(dir / "model.json") + " " +
                         quoted(dir / "nan.csv") + " --out " + quoted(dir / "migrated"));
  }();
  EXPECT_EQ(nan.status, 2);
  EXPECT_NE(nan.err.find("nan.csv:2"), std::string::npos) << nan.err;
  EXPECT_FALSE(fs::exists(dir / "migrated")) << "bad input, no output folder";
  // migrate never overwrites an input.
  write_file(dir / "w.csv", "name,x,y\ndock,6,4\n");
  const auto same = run_floorgrid("migrate --model " + quoted(dir / "model.json") + " " +
                                  quoted(dir / "w.csv") + " --out " + quoted(dir.path()));
  EXPECT_EQ(same.status, 2) << same.err;
  EXPECT_EQ(read_file(dir / "w.csv"), "name,x,y\ndock,6,4\n");
}

}  // namespace
}  // namespace floorgrid
