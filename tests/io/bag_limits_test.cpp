// The bag readers' chunk limit: 256 MiB at most, an eighth of the memory limit below that
// (io/logs/bag_file.hpp BagReadLimits).
#include <gtest/gtest.h>

#include <filesystem>

#include "floorgrid/io/logs/bag_file.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid::io {
namespace {

namespace fs = std::filesystem;
using test::expect_input_error;

const fs::path kSource = FLOORGRID_SOURCE_DIR;

TEST(BagBombs, TheChunkLimitFollowsTheMemoryLimit) {
  EXPECT_EQ(BagReadLimits{}.max_chunk_bytes, kMaxChunkBytes);
  EXPECT_EQ(bag_read_limits(1000.0).max_chunk_bytes, kMaxChunkBytes);  // never above 256 MiB
  EXPECT_EQ(bag_read_limits(0.5).max_chunk_bytes, 64ull << 20);        // an eighth of 0.5 GiB
  // fuzz/regressions/mcap-zstd-bomb-240m.mcap: 8 KB stating 240 MiB. Under a 64 MiB limit (as
  // under --memory-limit 0.5 and in the fuzzers) it is refused before anything is allocated.
  const fs::path bomb = kSource / "fuzz/regressions/mcap-zstd-bomb-240m.mcap";
  ASSERT_TRUE(fs::exists(bomb));
  expect_input_error([&] { mcap_contents(bomb, bag_read_limits(0.5)); },
                     {"at byte 33", "251658240", "67108864"});
}

}  // namespace
}  // namespace floorgrid::io
