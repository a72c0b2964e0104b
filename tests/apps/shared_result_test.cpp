// tests/support/shared_result.sh, which lets test processes share one result: made once, reused
// while the binary and the commands stay the same, nothing left behind by a command that fails.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_command;
using test::TempDir;

std::string script_line(const fs::path& cache, const std::string& name,
                        const std::string& command) {
  return quoted(fs::path(FLOORGRID_SOURCE_DIR) / "tests" / "support" / "shared_result.sh") + " " +
         quoted(FLOORGRID_BINARY) + " " + quoted(cache) + " " + quoted(fs::path(name)) + " " +
         quoted(fs::path(command));
}

TEST(SharedResult, IsMadeOnceThenReusedUntilTheCommandsChange) {
  TempDir cache;
  const std::string first = "simulate --preset office --seed 3 --out {}/data";
  const test::CommandResult made = run_command(script_line(cache.path(), "office", first));
  ASSERT_EQ(made.status, 0) << made.err;
  const fs::path folder = cache / "office";
  EXPECT_EQ(made.out, folder.string() + "\n");
  const fs::path truth = folder / "data" / "truth.json";
  ASSERT_TRUE(fs::exists(truth));
  const auto written = fs::last_write_time(truth);

  const test::CommandResult again = run_command(script_line(cache.path(), "office", first));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(again.out, made.out);
  EXPECT_EQ(fs::last_write_time(truth), written) << "the result was made again";

  // Other commands under the same name make it anew.
  const test::CommandResult other = run_command(
      script_line(cache.path(), "office", "simulate --preset office --seed 4 --out {}/data"));
  ASSERT_EQ(other.status, 0) << other.err;
  EXPECT_NE(test::read_file(truth), "");
  EXPECT_NE(fs::last_write_time(truth), written);
}

TEST(SharedResult, AFailingCommandLeavesNothingAndPassesItsStatusOn) {
  TempDir cache;
  const test::CommandResult r =
      run_command(script_line(cache.path(), "bad", "simulate --preset nope --out {}/data"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown preset 'nope'"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(cache / "bad"));
}

}  // namespace
}  // namespace floorgrid
