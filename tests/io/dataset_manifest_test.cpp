#include "floorgrid/io/dataset/dataset_manifest.hpp"

#include <gtest/gtest.h>

#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::expect_input_error;
using test::TempDir;
using test::write_file;

/// A folder with the files a manifest points at.
struct DatasetFolder {
  TempDir dir;
  DatasetFolder() {
    for (const char* f : {"plan.dxf", "grid.yaml", "log.carmen", "pairs.csv", "truth.json"}) {
      write_file(dir / f, "x");
    }
  }
  std::filesystem::path write(const std::string& text) const {
    write_file(dir / "dataset.yaml", text);
    return dir.path();
  }
};

const std::string kFull = R"(name: test building
floorplan: plan.dxf
floorplan_units: in
floorplan_scale: auto
floorplan_layers: ["A-WALL*", "S-COLS"]
floorplan_layers_exclude: ["*FURN*"]
gridmap: grid.yaml
log: log.carmen
initial_pose:
  plan: [1.0, 2.0, 0.5]
  grid: [-3.0, 4.0, -1.0]
laser: {max_range: 30.0, min_range: 0.02, start_angle: -1.5707963, angle_increment: 0.0087266463}
odometry_noise: [0.05, 0.01, 0.02, 0.05]
odometry_noise_seed: 7
truth:
  manual_pairs: pairs.csv
  warp: truth.json
)";

TEST(DatasetManifest, ReadsEveryKeyAndResolvesPaths) {
  DatasetFolder folder;
  const DatasetManifest m = read_manifest(folder.write(kFull));
  EXPECT_EQ(m.name, "test building");
  EXPECT_EQ(m.floorplan, folder.dir / "plan.dxf");
  EXPECT_EQ(m.floorplan_units, "in");
  EXPECT_FALSE(m.floorplan_scale.has_value());
  EXPECT_EQ(m.floorplan_layers, (std::vector<std::string>{"A-WALL*", "S-COLS"}));
  EXPECT_EQ(m.floorplan_layers_exclude, (std::vector<std::string>{"*FURN*"}));
  EXPECT_EQ(m.gridmap, folder.dir / "grid.yaml");
  ASSERT_TRUE(m.log.has_value());
  ASSERT_TRUE(m.initial_pose.has_value());
  EXPECT_EQ(m.initial_pose->plan.theta, 0.5);
  EXPECT_EQ(m.initial_pose->grid.x, -3.0);
  EXPECT_EQ(*m.laser.max_range, 30.0);
  EXPECT_EQ(*m.laser.angle_increment, 0.0087266463);
  EXPECT_EQ((*m.odometry_noise)[3], 0.05);
  EXPECT_EQ(m.odometry_noise_seed, 7u);
  EXPECT_EQ(*m.truth.warp, folder.dir / "truth.json");
}

TEST(DatasetManifest, WriteThenReadGivesTheSameManifest) {
  DatasetFolder folder;
  DatasetManifest m = read_manifest(folder.write(kFull));
  m.manifest_path = folder.dir / "copy.yaml";
  m.floorplan_scale = 1.03;
  write_manifest(m);
  const DatasetManifest back = read_manifest(folder.dir / "copy.yaml");
  EXPECT_EQ(back.floorplan, m.floorplan);
  EXPECT_EQ(back.floorplan_scale, m.floorplan_scale);
  EXPECT_EQ(back.floorplan_layers, m.floorplan_layers);
  EXPECT_EQ(back.initial_pose->grid.theta, m.initial_pose->grid.theta);
  EXPECT_EQ(back.laser.min_range, m.laser.min_range);
  EXPECT_EQ(back.odometry_noise, m.odometry_noise);
  EXPECT_EQ(back.truth.manual_pairs, m.truth.manual_pairs);
}

TEST(DatasetManifest, BadManifestsNameKeyAndLine) {
  DatasetFolder folder;
  const std::string base = "floorplan: plan.dxf\ngridmap: grid.yaml\n";
  const auto check = [&](const std::string& text, const std::vector<std::string>& parts) {
    auto expected = parts;
    expected.push_back("dataset.yaml");
    expect_input_error([&] { read_manifest(folder.write(text)); }, expected);
  };
  check(base + "colour: red\n", {":3:", "'colour'", "unknown key"});
  // A path too long for the file system threw std::filesystem_error (found by fuzzing).
  check("floorplan: " + std::string(5000, 'v') + "\ngridmap: grid.yaml\n",
        {":1:", "'floorplan'", "does not exist"});
  check(base + "laser: {max_range: 30, beams: 3}\n", {":3:", "'laser.beams'"});
  check(base + "laser: {max_range: -1}\n", {":3:", "'laser.max_range'"});
  check(base + "truth:\n  map: x\n", {":4:", "'truth.map'"});
  check("gridmap: grid.yaml\n", {"'floorplan'", "missing"});
  check("floorplan: nothere.dxf\ngridmap: grid.yaml\n", {":1:", "'floorplan'", "does not exist"});
  check(base + "floorplan_units: furlong\n", {":3:", "'floorplan_units'", "furlong"});
  check(base + "floorplan_scale: big\n", {":3:", "'floorplan_scale'"});
  check(base + "floorplan_scale: 0\n", {":3:", "'floorplan_scale'", "from 0.0001 to 10000"});
  check(base + "floorplan_scale: 1e300\n", {":3:", "'floorplan_scale'", "(got 1e+300)"});
  check(base + "odometry_noise: [0.1, 0.2]\n", {":3:", "'odometry_noise'", "4 numbers"});
  check(base + "initial_pose:\n  plan: [0, 0, 0]\n", {"'initial_pose.grid'", "missing"});
  check(base + "gridmap_resolution: abc\n", {":3:", "'gridmap_resolution'"});
  check("floorplan: [plan.dxf\n", {"syntax"});
  expect_input_error([&] { read_manifest(folder.dir / "sub"); }, {"sub", "no such"});
  TempDir empty;
  expect_input_error([&] { read_manifest(empty.path()); }, {"no dataset.yaml"});
}

}  // namespace
}  // namespace floorgrid::io
