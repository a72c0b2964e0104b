#pragma once

// The independent bag writers of tests/bags/ run from the tests: the fr079 CARMEN log turned
// into neutral records (carmen_to_records.py), then into an MCAP file (write_mcap.mjs, Node) or
// a rosbag2 sqlite3 folder (write_rosbag2_db3.py), each with a manifest of what it wrote and the
// serialized bytes of every topic.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "floorgrid/io/logs/bag_file.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::test {

using io::BagContents;
using io::BagMessageView;
using io::BagTopic;
using io::BagVisitor;

/// The records of the first `scans` scans of fr079, made once per process; empty (with `why`
/// set) when the shared data is missing.
std::filesystem::path bag_records(std::string& why);
/// Why the MCAP writer cannot run (node or tests/bags/node_modules missing), or "".
std::string mcap_writer_missing();

/// What a writer wrote and what a reader read, per topic.
struct TopicBytes {
  std::string type;
  std::uint64_t count = 0;
  std::int64_t first_ns = 0;
  std::int64_t last_ns = 0;
  std::vector<std::uint64_t> sizes;
  std::string bytes;  ///< every message's serialized bytes, one after the other
};
using BagBytes = std::map<std::string, TopicBytes>;

/// Runs a writer: `command` (shell) with " --manifest M --dump-dir D" appended; then the
/// manifest and dumps as BagBytes. Fails the test when it exits non-zero.
BagBytes run_writer(const std::string& command, const std::filesystem::path& work);
/// Reads every message of a bag with `read` (read_mcap or read_rosbag2_sqlite) into BagBytes.
BagBytes read_all(const std::filesystem::path& path,
                  BagContents (*read)(const std::filesystem::path&, const BagVisitor&,
                                      const std::set<std::string>*, const io::BagReadLimits&),
                  BagContents* contents = nullptr);
/// Expects what was read to be what was written: types, counts, times, sizes, bytes.
void expect_same(const BagBytes& written, const BagBytes& read);
/// Expects `contents` to list the written topics with their types, counts and times.
void expect_contents(const BagBytes& written, const BagContents& contents);

}  // namespace floorgrid::test

/// Skips the test, saying why, when the records or the MCAP writer cannot be had.
#define FLOORGRID_REQUIRE_BAG_RECORDS(records)      \
  std::filesystem::path records;                    \
  do {                                              \
    std::string why_;                               \
    records = ::floorgrid::test::bag_records(why_); \
    if (records.empty())                            \
      GTEST_SKIP() << why_;                         \
  } while (0)
