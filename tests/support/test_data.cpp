#include "tests/support/test_data.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid::test {

std::filesystem::path data_path(const std::string& relative) {
  const char* env = std::getenv("FLOORGRID_DATA");
  const std::filesystem::path root = env != nullptr ? env : FLOORGRID_DATA_DIR;
  return root / relative;
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info != nullptr ? std::string(info->test_suite_name()) + "." + info->name()
                                     : std::string("floorgrid");
  for (char& c : name) {
    if (c == '/')
      c = '_';
  }
  path_ = std::filesystem::temp_directory_path() / ("floorgrid-test-" + std::to_string(::getpid()) +
                                                    "-" + std::to_string(counter++) + "-" + name);
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {
std::string slurp(const std::filesystem::path& path) {
  std::string s = read_file(path);
  std::filesystem::remove(path);
  return s;
}
}  // namespace

CommandResult run_command(const std::string& command) {
  TempDir tmp;
  const auto out_path = tmp / "stdout";
  const auto err_path = tmp / "stderr";
  // The subshell makes the redirections apply to a whole pipeline, not its last stage.
  const std::string full =
      "( " + command + " ) >'" + out_path.string() + "' 2>'" + err_path.string() + "' </dev/null";
  const int raw = std::system(full.c_str());
  CommandResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = slurp(out_path);
  result.err = slurp(err_path);
  return result;
}

std::string quoted(const std::filesystem::path& path) {
  std::string out = "'";  // appended, not chained: GCC 12 warns falsely on "'" + s + "'"
  out += path.string();
  out += '\'';
  return out;
}

CommandResult run_floorgrid(const std::string& args) {
  return run_command(std::string("'") + FLOORGRID_BINARY + "' " + args);
}

std::filesystem::path shared_office_alignment() {
  const std::filesystem::path script =
      std::filesystem::path(FLOORGRID_SOURCE_DIR) / "tests" / "support" / "shared_office.sh";
  const CommandResult r = run_command(quoted(script) + " " + quoted(FLOORGRID_BINARY) + " " +
                                      quoted(FLOORGRID_TEST_CACHE_DIR));
  std::string folder = r.out;
  while (!folder.empty() && (folder.back() == '\n' || folder.back() == '\r'))
    folder.pop_back();
  EXPECT_EQ(r.status, 0) << "shared_office.sh made no result: " << r.out << r.err;
  return folder;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

ReferencePairs pairs_of(const std::vector<Eigen::Vector2d>& plan,
                        const std::vector<Eigen::Vector2d>& grid) {
  EXPECT_EQ(plan.size(), grid.size());
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, static_cast<Eigen::Index>(plan.size()));
  pairs.points_in_grid.resize(2, static_cast<Eigen::Index>(grid.size()));
  for (std::size_t i = 0; i < plan.size() && i < grid.size(); ++i) {
    pairs.points_in_plan.col(static_cast<Eigen::Index>(i)) = plan[i];
    pairs.points_in_grid.col(static_cast<Eigen::Index>(i)) = grid[i];
  }
  return pairs;
}

ReferencePairs pairs_through(const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& truth,
                             const Eigen::Matrix2Xd& points_in_plan) {
  ReferencePairs pairs;
  pairs.points_in_plan = points_in_plan;
  pairs.points_in_grid.resize(2, points_in_plan.cols());
  for (Eigen::Index i = 0; i < points_in_plan.cols(); ++i)
    pairs.points_in_grid.col(i) = truth(points_in_plan.col(i));
  return pairs;
}

std::unique_ptr<PointMapping> fitted(const std::string& model, const ReferencePairs& pairs) {
  MappingOptions options;
  options.model = model;
  std::unique_ptr<PointMapping> mapping = make_mapping(options);
  mapping->fit(pairs);
  return mapping;
}

}  // namespace floorgrid::test
