// `floorgrid fit` and `floorgrid map` end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "floorgrid/core/random.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::run_floorgrid;
using test::TempDir;
using test::write_file;

/// The truth: rotate by 0.5 rad, scale 1.1, shift (3, -2).
Eigen::Vector2d truth(const Eigen::Vector2d& p) {
  Eigen::Matrix2d R;
  R << std::cos(0.5), -std::sin(0.5), std::sin(0.5), std::cos(0.5);
  return 1.1 * R * p + Eigen::Vector2d(3.0, -2.0);
}

/// Pairs of the truth written in `unit`s (a pixel of 5 cm: unit 0.05).
void write_pairs(const fs::path& path, double unit) {
  Random r(5);
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 60);
  pairs.points_in_grid.resize(2, 60);
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector2d p(r.uniform(0, 30), r.uniform(0, 15));
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) = truth(p);
  }
  io::write_pairs_csv(pairs, path, unit);
}

TEST(FitAndMapCommands, FitThenMapPointsPosesAndCsv) {
  TempDir dir;
  write_pairs(dir / "pairs.csv", 1.0);
  const auto fit = run_floorgrid("fit --pairs " + quoted(dir / "pairs.csv") +
                                 " --model gt --cv 5 --out " + quoted(dir / "model.json"));
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(fit.out.find("inliers   60 of 60"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("cv error"), std::string::npos) << fit.out;
  const auto model = nlohmann::json::parse(read_file(dir / "model.json"));
  EXPECT_EQ(model["format"], "floorgrid-model");
  EXPECT_EQ(model["model"], "gt");
  EXPECT_EQ(model["frames"]["from"], "plan");
  EXPECT_EQ(model["parameters"]["T_grid_plan"].size(), 3u);
  EXPECT_TRUE(model["fit"]["cv_error_m"].is_number());
  EXPECT_EQ(model["fit"]["cv"]["kind"], "blocked");
  EXPECT_EQ(model["fit"]["cv"]["folds"], 5);
  EXPECT_GT(model["fit"]["cv"]["block_size_m"].get<double>(), 0.0);
  EXPECT_NE(fit.out.find("-fold blocked"), std::string::npos) << fit.out;
  // The threshold adapted to the pairs' noise, unless one is given (auto: the same as none).
  EXPECT_EQ(model["parameters"]["ransac"]["inlier_threshold_source"], "adaptive");
  for (const auto& [option, source] : {std::pair<std::string, std::string>{"0.3", "given"},
                                       std::pair<std::string, std::string>{"auto", "adaptive"}}) {
    ASSERT_EQ(run_floorgrid("fit --pairs " + quoted(dir / "pairs.csv") +
                            " --model gt --inlier-threshold " + option + " --out " +
                            quoted(dir / "given.json"))
                  .status,
              0);
    const auto given = nlohmann::json::parse(read_file(dir / "given.json"));
    EXPECT_EQ(given["parameters"]["ransac"]["inlier_threshold_source"], source);
    if (source == "given") {
      EXPECT_EQ(given["parameters"]["ransac"]["inlier_threshold_m"], 0.3);
    }
  }

  const auto one = run_floorgrid("map --model " + quoted(dir / "model.json") + " 10,5 10,5,0.25");
  ASSERT_EQ(one.status, 0) << one.err;
  const Eigen::Vector2d g = truth({10.0, 5.0});
  std::ostringstream expected;
  expected.precision(6);
  expected << std::fixed << g.x() << "," << g.y();
  EXPECT_NE(one.out.find("10,5 -> " + expected.str()), std::string::npos) << one.out;
  EXPECT_NE(one.out.find(expected.str() + "," + std::to_string(0.75).substr(0, 8)),
            std::string::npos)
      << one.out;  // the heading turns by the rotation

  write_file(dir / "in.csv", "x,y,theta\n10,5,0.25\n# a comment\n100,100,0\n");
  const auto csv = run_floorgrid("map --model " + quoted(dir / "model.json") + " --points " +
                                 quoted(dir / "in.csv") + " --out " + quoted(dir / "out.csv"));
  ASSERT_EQ(csv.status, 0) << csv.err;
  std::istringstream lines(read_file(dir / "out.csv"));
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header, "x,y,theta,std_m,nearest_pair_m,flag");
  double x = 0, y = 0, theta = 0;
  ASSERT_EQ(std::sscanf(first.c_str(), "%lf,%lf,%lf", &x, &y, &theta), 3) << first;
  EXPECT_NEAR(x, g.x(), 1e-9);
  EXPECT_NEAR(y, g.y(), 1e-9);
  EXPECT_NEAR(theta, 0.75, 1e-9);
  EXPECT_EQ(first.substr(first.rfind(',') + 1), "ok");
  EXPECT_EQ(second.substr(second.rfind(',') + 1), "outside_hull");

  // A bias the pairs share, given: in the model file and in every std_m, in quadrature.
  const auto biased =
      run_floorgrid("fit --pairs " + quoted(dir / "pairs.csv") +
                    " --model gt --shared-std 0.05 --out " + quoted(dir / "biased.json"));
  ASSERT_EQ(biased.status, 0) << biased.err;
  EXPECT_NE(biased.out.find(" + 0.0500^2) m"), std::string::npos) << biased.out;
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "biased.json"))["uncertainty"]["shared_std_m"],
            0.05);
  const auto std_of = [&](const fs::path& file) {
    const auto mapped = run_floorgrid("map --model " + quoted(file) + " --points " +
                                      quoted(dir / "in.csv") + " --out " + quoted(dir / "s.csv"));
    EXPECT_EQ(mapped.status, 0) << mapped.err;
    std::istringstream rows(read_file(dir / "s.csv"));
    std::string row;
    std::getline(rows, row);
    std::getline(rows, row);
    double values[4] = {};
    EXPECT_EQ(
        std::sscanf(row.c_str(), "%lf,%lf,%lf,%lf", &values[0], &values[1], &values[2], &values[3]),
        4)
        << row;
    return values[3];
  };
  const double plain = std_of(dir / "model.json");
  EXPECT_NEAR(std_of(dir / "biased.json"), std::hypot(plain, 0.05), 1e-6);
  EXPECT_NE(run_floorgrid("fit --pairs " + quoted(dir / "pairs.csv") + " --shared-std -1 --out " +
                          quoted(dir / "bad.json"))
                .err.find("--shared-std"),
            std::string::npos);

  const auto back = run_floorgrid("map --inverse --model " + quoted(dir / "model.json") + " " +
                                  std::to_string(g.x()) + "," + std::to_string(g.y()));
  ASSERT_EQ(back.status, 0) << back.err;
  EXPECT_NE(back.out.find("-> 10.0000"), std::string::npos) << back.out;
}

TEST(FitAndMapCommands, PairsInPixelsAreMappedInPixels) {
  TempDir dir;
  write_pairs(dir / "px.csv", 0.05);
  ASSERT_EQ(run_floorgrid("fit --pairs " + quoted(dir / "px.csv") +
                          " --model gt-affine --unit 0.05 --out " + quoted(dir / "m.json"))
                .status,
            0);
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "m.json"))["unit"], 0.05);
  const auto px = run_floorgrid("map --model " + quoted(dir / "m.json") + " 200,100");
  ASSERT_EQ(px.status, 0) << px.err;
  const Eigen::Vector2d g = truth({10.0, 5.0}) / 0.05;  // (200, 100) px is (10, 5) m
  std::ostringstream expected;
  expected.precision(6);
  expected << std::fixed << g.x();
  EXPECT_NE(px.out.find("-> " + expected.str()), std::string::npos) << px.out;
}

TEST(FitAndMapCommands, BadInputExitsWithTwoNamingTheProblem) {
  TempDir dir;
  write_pairs(dir / "pairs.csv", 1.0);
  ASSERT_EQ(run_floorgrid("fit --pairs " + quoted(dir / "pairs.csv") + " --model gt --out " +
                          quoted(dir / "m.json"))
                .status,
            0);
  auto model = nlohmann::json::parse(read_file(dir / "m.json"));
  model["version"] = 99;
  write_file(dir / "v99.json", model.dump());
  model["version"] = 1;
  model["model"] = "magic";
  write_file(dir / "magic.json", model.dump());
  write_file(dir / "broken.json", "{\n  \"format\": \"floorgrid-model\",\n  oops\n}\n");
  write_file(dir / "bad.csv", "x,z\n1,2\n");
  write_file(dir / "short.csv", "x,y\n1,2\n3\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"fit --pairs " + quoted(dir / "pairs.csv") + " --model nope --out " + quoted(dir / "x.json"),
       "nope"},
      {"fit --pairs " + quoted(dir / "missing.csv") + " --model gt --out " + quoted(dir / "x.json"),
       "missing.csv"},
      {"fit --pairs " + quoted(dir / "pairs.csv") + " --cv 1 --out " + quoted(dir / "x.json"),
       "--cv"},
      {"map --model " + quoted(dir / "v99.json") + " 1,2", "version"},
      {"map --model " + quoted(dir / "magic.json") + " 1,2", "magic"},
      {"map --model " + quoted(dir / "broken.json") + " 1,2", "broken.json:3"},
      {"map --model " + quoted(dir / "m.json") + " 1,x", "POINTS"},
      {"map --model " + quoted(dir / "m.json") + " --points " + quoted(dir / "bad.csv") +
           " --out " + quoted(dir / "o.csv"),
       "bad.csv:1"},
      {"map --model " + quoted(dir / "m.json") + " --points " + quoted(dir / "short.csv") +
           " --out " + quoted(dir / "o.csv"),
       "short.csv:3"},
      {"map --model " + quoted(dir / "m.json"), "--points"},
  };
  for (const auto& [args, expected] : cases) {
    const auto run = run_floorgrid(args);
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_NE(run.err.find(expected), std::string::npos) << args << ": " << run.err;
  }
  EXPECT_FALSE(fs::exists(dir / "x.json"));
  EXPECT_FALSE(fs::exists(dir / "o.csv"));
}

/// Runs `floorgrid args` and expects exit 2 with every part in its message.
void expect_refused(const std::string& args, const std::vector<std::string>& parts) {
  const auto r = run_floorgrid(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  for (const std::string& part : parts)
    EXPECT_NE(r.err.find(part), std::string::npos) << args << ": '" << r.err << "' lacks " << part;
}

TEST(FitAndMapCommands, BadOptionsAndNonPhysicalInputAreRefused) {
  TempDir dir;
  write_pairs(dir / "pairs.csv", 1.0);
  const std::string pairs = " --pairs " + quoted(dir / "pairs.csv");
  const std::string out = " --out " + quoted(dir / "model.json");
  // A negative budget used to wrap around to 18446744073709551611.
  expect_refused("fit --model tps --budget -5" + pairs + out, {"'--budget'", "-5"});
  // A fit whose dense matrices exceed the memory limit is refused before it starts (tps on 60
  // pairs needs about 127 kB: over a limit of 1 kB).
  expect_refused("fit --model tps --memory-limit 0.000001" + pairs + out,
                 {"'--budget'", "with 60 of the pairs", "more than the limit"});
  expect_refused("fit --model gt --extrapolation nan" + pairs + out, {"'--extrapolation'", "nan"});
  expect_refused("fit --model gt --inlier-threshold -1" + pairs + out,
                 {"'--inlier-threshold'", "-1"});
  expect_refused("fit --model gt --inlier-threshold 0.1m" + pairs + out,
                 {"'--inlier-threshold'", "auto or a distance", "0.1m"});
  // The output would overwrite the input.
  expect_refused("fit --model gt" + pairs + " --out " + quoted(dir / "." / "pairs.csv"),
                 {"'--out'", "also the input"});
  EXPECT_EQ(read_file(dir / "pairs.csv").substr(0, 28), "plan_x,plan_y,grid_x,grid_y\n");
  // Coordinates of 1e150 m are not physical; all-zero weights count nothing.
  write_file(dir / "far.csv", "plan_x,plan_y,grid_x,grid_y\n1e150,0,1,1\n0,1,2,2\n1,0,3,3\n");
  expect_refused("fit --model gt --pairs " + quoted(dir / "far.csv") + out,
                 {"far.csv:2", "'plan_x'", "not a physical coordinate"});
  write_file(dir / "zero.csv",
             "plan_x,plan_y,grid_x,grid_y,weight\n0,0,1,1,0\n0,1,2,2,0\n1,0,3,3,0\n");
  expect_refused("fit --model lc --pairs " + quoted(dir / "zero.csv") + out, {"every weight is 0"});
  // A model's own complaint about the pairs names the pairs file.
  write_file(dir / "two.csv", "plan_x,plan_y,grid_x,grid_y\n0,0,1,1\n1,1,2,2\n");
  expect_refused("fit --model lc --pairs " + quoted(dir / "two.csv") + out,
                 {"two.csv", "needs at least 3"});
  EXPECT_FALSE(std::filesystem::exists(dir / "model.json"));

  ASSERT_EQ(run_floorgrid("fit --model gt" + pairs + out).status, 0);
  expect_refused("map --model " + quoted(dir / "model.json") + " 1e300,0",
                 {"'POINTS'", "not a physical coordinate"});
  write_file(dir / "points.csv", "x,y\n1,2\n1e300,0\n");
  expect_refused("map --model " + quoted(dir / "model.json") + " --points " +
                     quoted(dir / "points.csv") + " --out " + quoted(dir / "mapped.csv"),
                 {"points.csv:3", "'x'"});
  expect_refused("map --model " + quoted(dir / "model.json") + " --points " +
                     quoted(dir / "points.csv") + " --out " + quoted(dir / "points.csv"),
                 {"also the input"});
}

TEST(FitAndMapCommands, APairFarFromTheOthersIsRefusedNamingItsLine) {
  // Issue 31, defect 3: one pair at (1e6, 1e6) among the others made `fit` exit 0 with "cv
  // error inf" and write a model that `map` refused.
  TempDir dir;
  write_pairs(dir / "pairs.csv", 1.0);
  std::string csv = read_file(dir / "pairs.csv");
  // Line 1 is the header, lines 2-61 the pairs: the far one on line 62, a comment before it.
  const Eigen::Vector2d far_grid = truth(Eigen::Vector2d(1e6, 1e6));
  csv += "# added by hand\n1000000,1000000," + std::to_string(far_grid.x()) + "," +
         std::to_string(far_grid.y()) + "\n";
  write_file(dir / "far.csv", csv);
  for (const char* model : {"tps", "gt", "lc"}) {
    const auto run = run_floorgrid("fit --pairs " + quoted(dir / "far.csv") + " --model " + model +
                                   " --cv 5 --out " + quoted(dir / "far.json"));
    EXPECT_EQ(run.status, 2) << model << "\n" << run.out << run.err;
    for (const std::string part : {"far.csv:63", "'plan_", "farther than"})
      EXPECT_NE(run.err.find(part), std::string::npos) << model << ": " << run.err;
    EXPECT_EQ(run.out.find("cv error  inf"), std::string::npos) << run.out;
    EXPECT_FALSE(fs::exists(dir / "far.json")) << model;
  }
  // A typo on the grid side is named too.
  csv = read_file(dir / "pairs.csv") + "5,5,-40000,3\n";
  write_file(dir / "far_grid.csv", csv);
  expect_refused("fit --model gt --pairs " + quoted(dir / "far_grid.csv") + " --out " +
                     quoted(dir / "far.json"),
                 {"far_grid.csv:62", "grid_x"});
  EXPECT_FALSE(fs::exists(dir / "far.json"));
}

}  // namespace
}  // namespace floorgrid
