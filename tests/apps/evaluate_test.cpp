// `floorgrid evaluate` end to end: on a simulated office, the numbers equal align's for the same
// model file; heat maps and overlay are written; bad input is exit 2 naming file and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quoted;
using test::read_json;
using test::run_floorgrid;
using test::TempDir;

/// One simulated office aligned, shared by the tests (align takes a while): made once for
/// every test process (test::shared_office_alignment) and copied, since the tests write beside it.
class EvaluateCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const fs::path shared = test::shared_office_alignment();
    ASSERT_TRUE(fs::exists(shared / "align" / "metrics.json")) << shared;
    fs::copy(shared / "data", *dir_ / "data", fs::copy_options::recursive);
    fs::copy(shared / "align", *dir_ / "align", fs::copy_options::recursive);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static TempDir* dir_;
};

TempDir* EvaluateCommand::dir_ = nullptr;

TEST_F(EvaluateCommand, AlignWritesHeatMapsForEveryModel) {
  const json m = read_json(*dir_ / "align" / "metrics.json");
  EXPECT_TRUE(m["timings_s"].contains("heat_maps"));
  for (const char* model : {"gt", "gp", "gpgt", "ct", "dt", "tps", "lc", "auto"}) {
    EXPECT_TRUE(fs::exists(*dir_ / "align" / "heatmaps" / (std::string("heat-") + model + ".png")))
        << model;
    EXPECT_TRUE(fs::exists(*dir_ / "align" / "heatmaps" / (std::string("std-") + model + ".png")))
        << model;
    const json& h = m["models"][model]["heat_map"];
    EXPECT_EQ(h["domain"], "warp") << model;
    EXPECT_GT(h["error"]["cells"].get<int>(), 10000) << model;
    EXPECT_GT(h["error"]["clip_m"].get<double>(), 0.0) << model;
  }
}

TEST_F(EvaluateCommand, NumbersEqualAlignsForTheSameModel) {
  const json a = read_json(*dir_ / "align" / "metrics.json");
  for (const char* model : {"gt", "dt", "tps", "gp"}) {
    const fs::path out = *dir_ / (std::string("eval-") + model);
    const auto run =
        run_floorgrid("evaluate " + quoted(*dir_ / "data") + " --model " +
                      quoted(*dir_ / "align" / (std::string("model-") + model + ".json")) +
                      " --out " + quoted(out));
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    const json e = read_json(out / "metrics.json");
    EXPECT_EQ(e["truth"], "warp");
    EXPECT_EQ(e["domain"], a["domain"]);
    const json& x = e["models"][model];
    const json& y = a["models"][model];
    for (const char* key : {"mean_error_m", "median_error_m", "p95_error_m", "max_error_m"})
      EXPECT_NEAR(x[key].get<double>(), y[key].get<double>(), 1e-9) << model << "." << key;
    EXPECT_EQ(x["error_histogram"], y["error_histogram"]) << model;
    EXPECT_EQ(x["back_and_forth"]["points"], y["back_and_forth"]["points"]) << model;
    EXPECT_NEAR(x["back_and_forth"]["max_m"].get<double>(),
                y["back_and_forth"]["max_m"].get<double>(), 1e-9)
        << model;
    EXPECT_EQ(x["cv_error_m"], y["cv_error_m"]) << model;
    EXPECT_NEAR(x["wall_distance_median_m"].get<double>(),
                y["wall_distance_median_m"].get<double>(), 1e-9)
        << model;
    EXPECT_EQ(x["heat_map"]["error"]["cells"], y["heat_map"]["error"]["cells"]) << model;
    EXPECT_NEAR(x["heat_map"]["error"]["p95_m"].get<double>(),
                y["heat_map"]["error"]["p95_m"].get<double>(), 1e-6)
        << model;
    for (const char* file : {"heatmaps/heat-", "heatmaps/std-", "overlays/overlay-"})
      EXPECT_TRUE(fs::exists(out / (std::string(file) + model + ".png"))) << file << model;
  }
}

TEST_F(EvaluateCommand, ModelFileOfAnotherFrameIsExitTwoNamingTheField) {
  json model = read_json(*dir_ / "align" / "model-gt.json");
  model["frames"] = {{"from", "grid"}, {"to", "plan"}};
  const fs::path bad = *dir_ / "model-frames.json";
  std::ofstream(bad) << model.dump();
  const auto run = run_floorgrid("evaluate " + quoted(*dir_ / "data") + " --model " + quoted(bad) +
                                 " --out " + quoted(*dir_ / "eval-bad"));
  EXPECT_EQ(run.status, 2) << run.out << run.err;
  EXPECT_NE(run.err.find("model-frames.json"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("frames"), std::string::npos) << run.err;
}

TEST_F(EvaluateCommand, DatasetWithoutTruthStillWritesUncertaintyAndDriftThenExitsTwo) {
  // The dataset without its truth block.
  const fs::path data = *dir_ / "data-no-truth";
  fs::copy(*dir_ / "data", data, fs::copy_options::recursive);
  std::ifstream in(data / "dataset.yaml");
  std::ostringstream kept;
  bool in_truth = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("truth:", 0) == 0) {
      in_truth = true;
      continue;
    }
    if (in_truth && (line.empty() || line[0] == ' '))
      continue;
    in_truth = false;
    kept << line << "\n";
  }
  in.close();
  std::ofstream(data / "dataset.yaml") << kept.str();
  const fs::path out = *dir_ / "eval-no-truth";
  const auto run =
      run_floorgrid("evaluate " + quoted(data) + " --model " +
                    quoted(*dir_ / "align" / "model-gp.json") + " --out " + quoted(out));
  EXPECT_EQ(run.status, 2) << run.out << run.err;
  EXPECT_NE(run.err.find("no truth"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("dataset.yaml"), std::string::npos) << run.err;
  const json e = read_json(out / "metrics.json");
  EXPECT_EQ(e["truth"], "none");
  const json& m = e["models"]["gp"];
  EXPECT_FALSE(m.contains("mean_error_m"));
  EXPECT_GT(m["back_and_forth"]["points"].get<int>(), 100);
  EXPECT_FALSE(m["heat_map"].contains("error"));
  EXPECT_EQ(m["heat_map"]["domain"], "model_observed");
  EXPECT_GT(m["heat_map"]["uncertainty"]["cells"].get<int>(), 10000);
  EXPECT_TRUE(fs::exists(out / "heatmaps" / "std-gp.png"));
  EXPECT_FALSE(fs::exists(out / "heatmaps" / "heat-gp.png"));
}

TEST_F(EvaluateCommand, MissingModelFileIsExitTwo) {
  const auto run =
      run_floorgrid("evaluate " + quoted(*dir_ / "data") + " --model " +
                    quoted(*dir_ / "nope.json") + " --out " + quoted(*dir_ / "eval-missing"));
  EXPECT_EQ(run.status, 2) << run.out << run.err;
  EXPECT_NE(run.err.find("nope.json"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace floorgrid
