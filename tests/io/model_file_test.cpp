// Model files are a trust boundary: files written by earlier builds load and map as they did,
// and a damaged or edited file is refused naming the file and the field (never a crash, a hang
// or an unbounded allocation).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(FLOORGRID_SOURCE_DIR) / "tests/fixtures/models";

// tests/fixtures/models holds model files fitted by the build before model files were checked
// field by field (commit 0b029d4: `floorgrid fit --pairs pairs.csv --model M --out M.json`) and
// expected.csv what its `floorgrid map` gave for four poses, forward and --inverse.
TEST(ModelFile, FilesOfAnEarlierBuildMapAsTheyDid) {
  std::ifstream in(kFixtures / "expected.csv");
  std::string line;
  std::getline(in, line);  // header
  int rows = 0;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string model, direction, cell;
    std::getline(fields, model, ',');
    std::getline(fields, direction, ',');
    double v[6];
    for (double& x : v) {
      std::getline(fields, cell, ',');
      x = std::stod(cell);
    }
    std::string flag;
    std::getline(fields, flag, ',');
    const auto mapping = io::read_model(kFixtures / (model + ".json"));
    const Pose2 pose{v[0], v[1], v[2]};
    const std::optional<Pose2> mapped = direction == "forward"
                                            ? std::optional<Pose2>(mapping->forward_pose(pose))
                                            : mapping->inverse_pose(pose);
    ASSERT_TRUE(mapped.has_value()) << line;
    // 1e-7 m and rad: the GP's solves differ by ~1e-8 between optimization levels (the
    // sanitizer build, other vector units); a format change moves points by far more.
    constexpr double kTolerance = 1e-7;
    EXPECT_NEAR(mapped->x, v[3], kTolerance) << line;
    EXPECT_NEAR(mapped->y, v[4], kTolerance) << line;
    EXPECT_NEAR(std::remainder(mapped->theta - v[5], 2 * M_PI), 0.0, kTolerance) << line;
    const MappedPoint point = direction == "forward" ? mapping->map_forward(pose.translation())
                                                     : mapping->map_inverse(pose.translation());
    EXPECT_EQ(to_string(point.flag), flag) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 80);
}

/// A model fitted in-process and its file's values, to damage.
Value fitted_file(const std::string& model) {
  MappingOptions options;
  options.model = model;
  const auto mapping = make_mapping(options);
  mapping->fit(io::read_pairs_csv(kFixtures / "pairs.csv"));
  return mapping->to_model_file();
}

void expect_text_refused(const std::string& json, const std::vector<std::string>& parts) {
  test::TempDir dir;
  test::write_file(dir / "model.json", json);
  std::vector<std::string> all = parts;
  all.push_back("model.json");
  test::expect_input_error([&] { io::read_model(dir / "model.json"); }, all);
}

void expect_refused(const Value& file, const std::vector<std::string>& parts) {
  expect_text_refused(io::dump_json(file), parts);
}

TEST(ModelFile, RefusesCoordinatesThatAreNotPhysical) {
  // A dt model with plan points near 1e300 crashed the Delaunay triangulation.
  Value dt = fitted_file("dt");
  dt["parameters"]["plan"] = Value::array(
      {Value::array({1e300, 1e300}), Value::array({0.0, 1.0}), Value::array({1.0, 0.0})});
  expect_refused(dt, {"'parameters.plan'", "1e+300"});
  Value support = fitted_file("gt");
  support["support"]["grid"] = Value::array({Value::array({0.0, 1e150})});
  expect_refused(support, {"'support.grid'"});
}

TEST(ModelFile, RefusesSizesThatWouldHangOrExhaustMemory) {
  // lc with neighbours 0 searched forever; 1e9 allocated gigabytes.
  for (const Value& n : {Value(0), Value(1e9), Value(-3), Value("12")}) {
    Value lc = fitted_file("lc");
    lc["parameters"]["neighbours"] = n;
    expect_refused(lc, {"'parameters.neighbours'"});
  }
  Value gp = fitted_file("gp");
  gp["parameters"]["lattice"]["max_nodes"] = Value(1e15);
  expect_refused(gp, {"'parameters.lattice.max_nodes'"});
  Value tps = fitted_file("tps");
  tps["parameters"]["lattice_spacing_m"] = 1e-300;
  expect_refused(tps, {"'parameters.lattice_spacing_m'"});
}

TEST(ModelFile, RefusesWrongTypesNamingTheField) {
  Value gt = fitted_file("gt");
  gt["parameters"]["T_grid_plan"] = "x";
  expect_refused(gt, {"'parameters.T_grid_plan'", "3 x 3"});
  Value singular = fitted_file("gt");
  singular["parameters"]["T_grid_plan"] =
      Value::array({Value::array({0.0, 0.0, 1.0}), Value::array({0.0, 0.0, 1.0}),
                    Value::array({0.0, 0.0, 1.0})});
  expect_refused(singular, {"'parameters.T_grid_plan'"});
  Value gp = fitted_file("gp");
  gp["parameters"]["signal_std_m"] = "large";
  expect_refused(gp, {"'parameters.signal_std_m'", "finite number"});
  Value auto_model = fitted_file("auto");
  auto_model["parameters"]["model"]["model"] = "auto";
  expect_refused(auto_model, {"'parameters.model.model'"});
}

TEST(ModelFile, RefusesAUnitOutsideAMicrometreToAThousandKilometres) {
  for (const double unit : {1e-320, 0.0, -1.0, 1e9}) {
    Value gt = fitted_file("gt");
    gt["unit"] = unit;
    expect_refused(gt, {"'unit'"});
  }
}

TEST(ModelFile, RefusesTextThatIsNotJsonOrNestedTooDeep) {
  expect_text_refused(std::string(10000, '[') + std::string(10000, ']'), {"nested deeper than 64"});
  expect_text_refused("{\"format\": \"floorgrid-model\", \"unit\": 1e999}", {"number overflow"});
  expect_text_refused("{\n\"format\": \n", {"not valid JSON", ":3:"});
  expect_text_refused("[1, 2]", {"'format'", "not a floorgrid model file"});
}

TEST(ModelFile, GtRecordsTheInlierThresholdItUsed) {
  const ReferencePairs pairs = io::read_pairs_csv(kFixtures / "pairs.csv");
  MappingOptions options;
  options.model = "gt";
  const auto adaptive = make_mapping(options);
  adaptive->fit(pairs);
  Value file = adaptive->to_model_file();
  Value& ransac = file["parameters"]["ransac"];
  EXPECT_EQ(ransac["inlier_threshold_source"].as_string(), "adaptive");
  const double used = ransac["inlier_threshold_m"].as_number();
  EXPECT_EQ(used, file["fit"]["details"]["inlier_threshold_m"].as_number());
  EXPECT_GT(used, 0.0);
  EXPECT_NEAR(used, 3.0 * file["fit"]["details"]["noise_sigma_m"].as_number(), 1e-12);

  options.ransac.inlier_threshold = 0.25;
  const auto given = make_mapping(options);
  given->fit(pairs);
  Value given_file = given->to_model_file();
  EXPECT_EQ(given_file["parameters"]["ransac"]["inlier_threshold_source"].as_string(), "given");
  EXPECT_EQ(given_file["parameters"]["ransac"]["inlier_threshold_m"].as_number(), 0.25);

  // Loaded and written again, the record stays; a file of an earlier build (a fixed 0.1 m and
  // no source) loads as given; an unknown source is refused.
  test::TempDir dir;
  test::write_file(dir / "model.json", io::dump_json(file));
  EXPECT_EQ(io::read_model(dir / "model.json")->to_model_file()["parameters"]["ransac"],
            file["parameters"]["ransac"]);
  Value old = io::read_model(kFixtures / "gt.json")->to_model_file();
  EXPECT_EQ(old["parameters"]["ransac"]["inlier_threshold_m"].as_number(), 0.1);
  EXPECT_EQ(old["parameters"]["ransac"]["inlier_threshold_source"].as_string(), "given");
  Value bad = file;
  bad["parameters"]["ransac"]["inlier_threshold_source"] = "guessed";
  expect_refused(bad, {"'parameters.ransac.inlier_threshold_source'", "guessed"});
}

TEST(ModelFile, ASummaryWithoutFiguresStillLoads) {
  // `fit` wrote rms_m as null for pairs it could not measure; `map` must read what `fit` wrote.
  Value gp = fitted_file("gp");
  gp["fit"]["rms_m"] = nullptr;
  gp["fit"]["cv_error_m"] = nullptr;
  test::TempDir dir;
  test::write_file(dir / "model.json", io::dump_json(gp));
  const auto mapping = io::read_model(dir / "model.json");
  EXPECT_TRUE(mapping->forward({3.0, 4.0}).allFinite());
}

}  // namespace
}  // namespace floorgrid

namespace floorgrid {
namespace {

TEST(ModelFile, RecordsWhichCrossValidationMeasuredTheError) {
  // auto records the cross-validation it chose by (blocked by default) with its error.
  Value chooser = fitted_file("auto");
  EXPECT_EQ(chooser["fit"]["cv"]["kind"].as_string(), "blocked");
  EXPECT_GT(chooser["fit"]["cv"]["block_size_m"].as_number(), 0.0);
  EXPECT_TRUE(chooser["fit"]["cv_error_m"].is_number());
  // The record reads back as written.
  test::TempDir dir;
  test::write_file(dir / "model.json", io::dump_json(chooser));
  const auto loaded = io::read_model(dir / "model.json");
  ASSERT_TRUE(loaded->summary().cv.has_value());
  EXPECT_EQ(loaded->summary().cv->kind, "blocked");
  EXPECT_EQ(loaded->summary().cv->folds, 5u);
  EXPECT_EQ(loaded->to_model_file()["fit"]["cv"], chooser["fit"]["cv"]);
  // A file of an earlier build has no record: it loads without one.
  EXPECT_FALSE(io::read_model(kFixtures / "gt.json")->summary().cv.has_value());
  Value bad = chooser;
  bad["fit"]["cv"]["kind"] = "spatial";
  expect_refused(bad, {"'fit.cv.kind'", "spatial"});
  bad = chooser;
  bad["fit"]["cv"]["block_size_m"] = -1.0;
  expect_refused(bad, {"'fit.cv.block_size_m'"});
}

}  // namespace
}  // namespace floorgrid
