// Files that are endless, say a key twice, hold several documents, or hold a model no fit makes
// (issue 31): each is refused naming the file, the line and the field, quickly, not read as
// something else.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/options/options_schema.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::expect_input_error;
using test::TempDir;

/// What `read` did in a child process limited to 2 GiB of address space: "refused: <message>"
/// for an InputError, else how it ended (an endless read fails its allocation there rather
/// than taking the machine's memory).
std::string in_child_with_2gib(const std::function<void()>& read) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0)
    return "no pipe";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(pipe_fds[0]);
#if !defined(__SANITIZE_ADDRESS__)
    // (AddressSanitizer's shadow memory alone is more address space than that.)
    const rlimit limit{2ull << 30, 2ull << 30};
    ::setrlimit(RLIMIT_AS, &limit);
#endif
    std::string answer;
    try {
      read();
      answer = "read";
    } catch (const InputError& e) {
      answer = std::string("refused: ") + e.what();
    } catch (const std::exception& e) {
      answer = std::string("failed: ") + e.what();
    }
    [[maybe_unused]] const ssize_t written = ::write(pipe_fds[1], answer.data(), answer.size());
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  std::string answer;
  char buffer[4096];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
    answer.append(buffer, static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  return answer.empty() ? "died" : answer;
}

// ---- endless files (defect 8) ----

TEST(EndlessFiles, AnOptionsFileOrModelThatNeverEndsIsRefusedAfterItsBound) {
  // /dev/zero as --config took 8.6 GB, as --model 4.9 GB, before anything said no.
  const auto start = std::chrono::steady_clock::now();
  const std::string config = in_child_with_2gib([] {
    JobOptions options;
    io::read_options_yaml("/dev/zero", io::job_option_tree(options));
  });
  EXPECT_NE(config.find("refused: /dev/zero: holds more than"), std::string::npos) << config;
  const std::string model = in_child_with_2gib([] { io::read_model("/dev/zero"); });
  EXPECT_NE(model.find("refused: /dev/zero: holds more than"), std::string::npos) << model;
  const std::string manifest = in_child_with_2gib([] { io::read_manifest("/dev/zero"); });
  EXPECT_NE(manifest.find("refused: /dev/zero: holds more than"), std::string::npos) << manifest;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

// ---- keys given twice, several documents (defect 14) ----

TEST(StrictYaml, AnOptionGivenTwiceIsRefusedAtItsSecondLine) {
  TempDir dir;
  test::write_file(dir / "twice.yaml",
                   "raster:\n  resolution: 0.1\n  margin: 3\n  resolution: 0.2\n");
  JobOptions options;
  expect_input_error(
      [&] { io::read_options_yaml(dir / "twice.yaml", io::job_option_tree(options)); },
      {"twice.yaml:4:", "raster.resolution", "given twice", "first on line 2"});
}

TEST(StrictYaml, AnOptionsFileOfTwoDocumentsIsRefused) {
  // yaml-cpp's Load reads the first document: the second was ignored silently.
  TempDir dir;
  test::write_file(dir / "two.yaml", "raster:\n  resolution: 0.1\n---\nraster:\n  margin: 3\n");
  JobOptions options;
  expect_input_error([&] { io::read_options_yaml(dir / "two.yaml", io::job_option_tree(options)); },
                     {"two.yaml:4:", "2 YAML documents"});
}

TEST(StrictYaml, AStrayCommaIsASyntaxErrorNotAHang) {
  // yaml-cpp 0.7's LoadAll never returned on the first three (found by the map_yaml and
  // dataset_yaml fuzzers in CI): it started one empty document after another at the comma.
  TempDir dir;
  struct Case {
    std::string text, line, says;
  };
  const std::vector<Case> cases = {{",ia", ":1:", "unexpected ','"},
                                   {"[a],b", ":1:", "unexpected ','"},
                                   {"- a\n,", ":2:", "unexpected ','"},
                                   {"image: map.pgm\nresolution: 0.05\n,\n", ":3:", "end of map"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    test::write_file(dir / "map.yaml", c.text);
    expect_input_error([&] { io::read_map_yaml(dir / "map.yaml"); },
                       {"map.yaml" + c.line, "YAML syntax error", c.says});
    test::write_file(dir / "dataset.yaml", c.text);
    expect_input_error([&] { io::read_manifest(dir / "dataset.yaml"); },
                       {"dataset.yaml" + c.line, "YAML syntax error", c.says});
  }
}

TEST(StrictYaml, AManifestWithAKeyTwiceIsRefused) {
  TempDir dir;
  test::write_file(dir / "dataset.yaml",
                   "floorplan: a.png\nfloorplan_resolution: 0.05\ngridmap: b.png\n"
                   "gridmap_resolution: 0.05\nfloorplan: c.png\n");
  expect_input_error([&] { io::read_manifest(dir / "dataset.yaml"); },
                     {"dataset.yaml:5:", "floorplan", "given twice"});
}

// ---- model files (defects 9, 11 and the unit given twice of 14) ----

/// A model of `name` fitted to a smooth warp of a 12 x 12 lattice, as its file's JSON.
nlohmann::json model_json(const std::string& name) {
  Eigen::Matrix2Xd plan(2, 144);
  for (int i = 0; i < 144; ++i)
    plan.col(i) << (i % 12) * 1.5, (i / 12) * 1.5;
  const auto warp = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(2.0 + 0.98 * p.x() + 0.02 * std::sin(p.y()), -1.0 + 1.01 * p.y());
  };
  const auto mapping = test::fitted(name, test::pairs_through(warp, plan));
  return nlohmann::json::parse(io::dump_json(mapping->to_model_file()));
}

TEST(ModelFiles, AKeyGivenTwiceIsRefusedAtItsLine) {
  // The last "unit" won: a model of mm pairs read as m mapped 1000x off.
  TempDir dir;
  std::string text = model_json("gt").dump(1);
  const std::size_t at = text.find("\"unit\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "\"unit\": 0.001,\n ");
  test::write_file(dir / "model.json", text);
  const long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + at + 20, '\n'));
  expect_input_error([&] { io::read_model(dir / "model.json"); },
                     {"model.json:" + std::to_string(line) + ":", "unit", "given twice"});
}

TEST(ModelFiles, KernelWeightsOfAbsurdSizeAreRefusedAtLoad) {
  // tps kernel weights of 1e300: every field finite, the mapping at 1e303 m, flagged ok; exports
  // then wrote NaN and inf.
  TempDir dir;
  nlohmann::json model = model_json("tps");
  for (auto& w : model["parameters"]["kernel_weights"])
    for (auto& v : w)
      v = v.get<double>() * 1e300 + 1e300;
  test::write_file(dir / "tps.json", model.dump());
  expect_input_error([&] { io::read_model(dir / "tps.json"); },
                     {"tps.json", "parameters", "not a plausible mapping"});
  // The file as fitted loads.
  test::write_file(dir / "fitted.json", model_json("tps").dump());
  EXPECT_NO_THROW(io::read_model(dir / "fitted.json"));
}

TEST(ModelFiles, AnLcModelOfIdenticalPointsIsRefusedAtOnce) {
  // 511 identical support points: mapping 3 points took 35 s, every triangle search in vain.
  TempDir dir;
  nlohmann::json model = model_json("lc");
  for (auto& p : model["parameters"]["plan"])
    p = model["parameters"]["plan"][0];
  test::write_file(dir / "lc.json", model.dump());
  const auto start = std::chrono::steady_clock::now();
  const std::string answer = in_child_with_2gib([&] {
    const auto mapping = io::read_model(dir / "lc.json");
    for (int i = 0; i < 3; ++i)
      mapping->map_forward(Eigen::Vector2d(i, i));
  });
  EXPECT_NE(answer.find("refused:"), std::string::npos) << answer;
  EXPECT_NE(answer.find("parameters.plan"), std::string::npos) << answer;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ModelFiles, APointMappedBeyondThePlausibleRangeGetsNoNumber) {
  // A sound model can still be asked far out: twice 6e6 m is no coordinate (1e7 m at most), and
  // was answered as a number flagged outside_hull.
  Eigen::Matrix2Xd plan(2, 16);
  for (int i = 0; i < 16; ++i)
    plan.col(i) << (i % 4) * 3.0, (i / 4) * 2.0;
  const auto mapping = test::fitted(
      "gt-affine", test::pairs_through([](const Eigen::Vector2d& p) { return 2.0 * p; }, plan));
  const MappedPoint near = mapping->map_forward(Eigen::Vector2d(1.0, 1.0));
  EXPECT_NEAR(near.point.x(), 2.0, 1e-9);
  const MappedPoint far = mapping->map_forward(Eigen::Vector2d(6e6, 0.0));
  EXPECT_EQ(far.flag, MapFlag::not_invertible);
  EXPECT_TRUE(std::isnan(far.point.x()) && std::isnan(far.point.y()));
  const MappedPoint back = mapping->map_inverse(Eigen::Vector2d(9e6, 0.0));
  EXPECT_EQ(back.flag, MapFlag::outside_hull);  // 4.5e6 m in the plan: a number
  EXPECT_NEAR(back.point.x(), 4.5e6, 1e-3);
}

// ---- options out of range, refused where the file is read (defects 12 and 14) ----

struct BadOption {
  std::string yaml;   ///< the file
  long line;          ///< where the error must point
  std::string key;    ///< the option it must name
  std::string words;  ///< part of the rule
};

TEST(OptionRanges, EveryBadValueIsRefusedWithFileLineAndKey) {
  const std::vector<BadOption> cases = {
      {"raster:\n  resolution: 0\n", 2, "raster.resolution", "in [0.001, 10]"},
      {"raster:\n  resolution: -0.05\n", 2, "raster.resolution", "in [0.001, 10]"},
      {"raster:\n  resolution: .inf\n", 2, "raster.resolution", "in [0.001, 10]"},
      {"raster:\n  margin: 1e12\n", 2, "raster.margin", "in [0, 1000]"},
      {"raster:\n  wall_thickness: 1e9\n", 2, "raster.wall_thickness", "in [0, 10]"},
      {"limits:\n  memory_gb: -1\n", 2, "limits.memory_gb", "in [0, 1000000)"},
      {"align:\n  localization:\n    plan:\n      filter:\n        tracking_particles: 0\n", 5,
       "align.localization.plan.filter.tracking_particles", "in [1, 1000000]"},
      {"align:\n  localization:\n    grid:\n      filter:\n        global_particles: "
       "1000000000000\n",
       5, "align.localization.grid.filter.global_particles", "in [1, 10000000]"},
      {"align:\n  localization:\n    plan:\n      filter:\n        seeding:\n          batch: 0\n",
       6, "align.localization.plan.filter.seeding.batch", "in [1, 1000000]"},
      {"align:\n  localization:\n    plan:\n      filter:\n        recovery:\n"
       "          recovery_fraction: 2\n",
       6, "align.localization.plan.filter.recovery.recovery_fraction", "in (0, 1]"},
      {"align:\n  models:\n    mapping:\n      ransac:\n        max_iterations: 0\n", 5,
       "align.models.mapping.ransac.max_iterations", "in [1, 1000000000]"},
      {"align:\n  models:\n    mapping:\n      gp:\n        tuning:\n          rprop:\n"
       "            max_iterations: 0\n",
       7, "align.models.mapping.gp.tuning.rprop.max_iterations", "in [1, 1000000]"},
      {"align:\n  localization:\n    plan:\n      runner:\n        match:\n"
       "          max_iterations: 0\n",
       6, "align.localization.plan.runner.match.max_iterations", "in [1, 10000]"},
      {"align:\n  localization:\n    scale_search:\n      range:\n        min: 2\n        max: 1\n",
       6, "align.localization.scale_search.range.max", ">= min"},
      {"units:\n  registration:\n    min_scale: 5\n", 3, "units.registration.max_scale",
       ">= min_scale"},
      {"units:\n  registration:\n    scale_step: 0\n", 3, "units.registration.scale_step",
       "in [0.001, 1]"},
      {"align:\n  localization:\n    threads: 0\n", 3, "align.localization.threads", "in [1, 256]"},
      {"align:\n  localization:\n    threads: 1000000\n", 3, "align.localization.threads",
       "in [1, 256]"},
      {"align:\n  models:\n    mapping:\n      tps:\n        lattice:\n          threads: 3\n", 6,
       "align.models.mapping.tps.lattice.threads", "in [1, 2]"},
      {"align:\n  models:\n    cv_folds: 1\n", 3, "align.models.cv_folds", "0 (no cross"},
  };
  for (const BadOption& c : cases) {
    TempDir dir;
    test::write_file(dir / "bad.yaml", c.yaml);
    JobOptions options;
    expect_input_error(
        [&] { io::read_options_yaml(dir / "bad.yaml", io::job_option_tree(options)); },
        {"bad.yaml:" + std::to_string(c.line) + ":", "'" + c.key + "'", "must be", c.words});
  }
}

TEST(OptionRanges, ValuesInsideTheirRangesAreRead) {
  TempDir dir;
  test::write_file(dir / "good.yaml",
                   "raster:\n  resolution: 0.001\n  margin: 1000\n  wall_thickness: 0\n"
                   "limits:\n  memory_gb: 0\n"
                   "align:\n  localization:\n    threads: 1\n    scale_search:\n      range:\n"
                   "        min: 1\n        max: 1\n");
  JobOptions options;
  io::read_options_yaml(dir / "good.yaml", io::job_option_tree(options));
  EXPECT_EQ(options.raster.resolution, 0.001);
  EXPECT_EQ(options.raster.margin, 1000.0);
  EXPECT_EQ(options.align.localization.threads, 1);
  EXPECT_EQ(options.align.localization.scale_search.range.max, 1.0);
}

}  // namespace
}  // namespace floorgrid
