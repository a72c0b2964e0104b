#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::test {

/// Path of a file in the shared real data folder (../shared/data beside the checkout).
std::filesystem::path data_path(const std::string& relative);

/// A fresh, empty temporary folder for one test, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The folder.
  const std::filesystem::path& path() const { return path_; }
  /// A path inside the folder.
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Pairs of plan and grid points given side by side (equal lengths), in that order.
ReferencePairs pairs_of(const std::vector<Eigen::Vector2d>& plan,
                        const std::vector<Eigen::Vector2d>& grid);

/// Pairs at `points_in_plan` and where `truth` takes each of them in the grid.
ReferencePairs pairs_through(const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& truth,
                             const Eigen::Matrix2Xd& points_in_plan);

/// `model` (one of mapping_model_names()) fitted to `pairs` with its default options.
std::unique_ptr<PointMapping> fitted(const std::string& model, const ReferencePairs& pairs);

/// Writes `text` to `path` (binary, exact bytes).
void write_file(const std::filesystem::path& path, const std::string& text);
/// Reads a whole file as bytes.
std::string read_file(const std::filesystem::path& path);

/// A JSON file parsed (a test fails on bad JSON with the parser's exception).
nlohmann::json read_json(const std::filesystem::path& path);

/// Result of running a command: exit status and captured output.
struct CommandResult {
  int status = -1;  ///< exit status
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};
/// `path` in single quotes, for a shell command line.
std::string quoted(const std::filesystem::path& path);
/// Runs the built floorgrid binary with `args` (a shell-quoted argument string).
CommandResult run_floorgrid(const std::string& args);
/// Runs a shell command.
CommandResult run_command(const std::string& command);

/// The simulated office of seed 2, aligned with the defaults: `data/` and `align/` in the
/// folder. Made once per floorgrid binary by tests/support/shared_office.sh (shared_result.sh,
/// under FLOORGRID_TEST_CACHE_DIR), since ctest runs each test in a process of its own and a
/// suite's SetUpTestSuite would align it again for every test. EvaluateCommand, the report's and
/// the viewer's browser tests read it; the folder is shared, so copy what a test changes. A
/// failure fails the calling test with the script's output.
std::filesystem::path shared_office_alignment();

}  // namespace floorgrid::test

/// Skips the current test, printing why, when a shared data file is missing.
#define FLOORGRID_REQUIRE_DATA(relative)                                                 \
  do {                                                                                   \
    if (!std::filesystem::exists(::floorgrid::test::data_path(relative))) {              \
      GTEST_SKIP() << "shared data missing: " << ::floorgrid::test::data_path(relative); \
    }                                                                                    \
  } while (0)
