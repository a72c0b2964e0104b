// The MCAP reader against files of an independent writer (tests/bags/write_mcap.mjs: the MCAP
// project's @mcap/core with Foxglove's CDR serializer) holding fr079 as ROS 2 messages.
#include <gtest/gtest.h>

#include <cstring>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/rosbag2_folder.hpp"
#include "tests/support/bag_writers.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::quoted;

const std::filesystem::path kBags = std::filesystem::path(FLOORGRID_SOURCE_DIR) / "tests/bags";

#define FLOORGRID_REQUIRE_MCAP_WRITER()                                    \
  do {                                                                     \
    if (const std::string why = test::mcap_writer_missing(); !why.empty()) \
      GTEST_SKIP() << why;                                                 \
  } while (0)

// Writes an MCAP of the fr079 records with `options`; its path, and what the writer wrote.
std::filesystem::path write_mcap(const test::TempDir& dir, const std::filesystem::path& records,
                                 const std::string& options, test::BagBytes& written) {
  const std::filesystem::path out = dir / "run.mcap";
  written = test::run_writer("node " + quoted(kBags / "write_mcap.mjs") + " " + quoted(records) +
                                 " " + quoted(out) + " " + options,
                             dir.path());
  return out;
}

struct Variant {
  const char* name;
  const char* options;
  const char* warning;  ///< in the contents' warning, or null for none
};

class McapVariants : public ::testing::TestWithParam<Variant> {};

TEST_P(McapVariants, ContentsAndMessagesAreWhatTheWriterWrote) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  FLOORGRID_REQUIRE_MCAP_WRITER();
  const test::TempDir dir;
  test::BagBytes written;
  // Small chunks: many of them, each topic spread over several.
  const auto path =
      write_mcap(dir, records, std::string(GetParam().options) + " --chunk-size 20000", written);
  ASSERT_EQ(written.at("/scan").count, 120u);

  const BagContents contents = mcap_contents(path);
  EXPECT_EQ(contents.format, BagFormat::mcap);
  test::expect_contents(written, contents);
  EXPECT_EQ(contents.topics.front().topic, "/tf_static") << "topics in the file's order";
  if (GetParam().warning == nullptr) {
    EXPECT_TRUE(contents.warnings.empty()) << contents.warnings.front();
  } else {
    ASSERT_EQ(contents.warnings.size(), 1u);
    EXPECT_NE(contents.warnings[0].find(GetParam().warning), std::string::npos)
        << contents.warnings[0];
  }

  BagContents counted;
  const test::BagBytes read = test::read_all(path, &read_mcap, &counted);
  test::expect_same(written, read);
  test::expect_contents(written, counted);
  EXPECT_EQ(counted.start_ns, contents.start_ns);
  EXPECT_EQ(counted.end_ns, contents.end_ns);
}

INSTANTIATE_TEST_SUITE_P(
    Writer, McapVariants,
    ::testing::Values(Variant{"lz4", "--compression lz4", nullptr},
                      Variant{"zstd", "--compression zstd", nullptr},
                      Variant{"none", "--compression none", nullptr},
                      Variant{"lz4_no_summary", "--compression lz4 --no-summary", "no summary"},
                      Variant{"zstd_no_summary", "--compression zstd --no-summary", "no summary"},
                      Variant{"none_no_summary", "--compression none --no-summary", "no summary"},
                      Variant{"unchunked", "--no-chunks", "unchunked file?"},
                      Variant{"unchunked_no_summary", "--no-chunks --no-summary", "no summary"},
                      Variant{"no_odom", "--compression lz4 --no-odom", nullptr}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(McapReader, VisitsOnlyTheTopicsAskedFor) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  FLOORGRID_REQUIRE_MCAP_WRITER();
  const test::TempDir dir;
  test::BagBytes written;
  const auto path = write_mcap(dir, records, "--compression zstd", written);
  const std::set<std::string> wanted = {"/scan"};
  std::uint64_t visited = 0;
  const BagContents counted = read_mcap(
      path,
      [&](const BagTopic& topic, const BagMessageView&) {
        EXPECT_EQ(topic.topic, "/scan");
        ++visited;
      },
      &wanted);
  EXPECT_EQ(visited, 120u);
  test::expect_contents(written, counted);  // every topic still counted
}

TEST(McapReader, ReadsARosbag2FolderOfMcapFiles) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  FLOORGRID_REQUIRE_MCAP_WRITER();
  const test::TempDir dir;
  test::BagBytes written;
  const auto path = write_mcap(dir, records, "--compression lz4", written);
  const std::filesystem::path folder = dir / "bag";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(path, folder / "bag_0.mcap");
  std::filesystem::copy_file(path, folder / "bag_1.mcap");
  test::write_file(folder / "metadata.yaml",
                   "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n"
                   "  relative_file_paths:\n    - bag_0.mcap\n    - bag_1.mcap\n");
  EXPECT_EQ(rosbag2_folder_format(folder), BagFormat::mcap);
  const BagContents contents = mcap_contents(folder);
  ASSERT_EQ(contents.topics.size(), written.size());
  for (const BagTopic& topic : contents.topics)
    EXPECT_EQ(topic.messages, 2 * written.at(topic.topic).count) << topic.topic;
  std::uint64_t visited = 0;
  read_mcap(
      folder, [&](const BagTopic&, const BagMessageView&) { ++visited; }, nullptr);
  EXPECT_EQ(visited, contents.messages);
}

// ---- the committed seed (tests/bags/fr079_small.mcap): no writer needed ----

TEST(McapReader, ReadsTheCommittedSmallFile) {
  const std::filesystem::path path = kBags / "fr079_small.mcap";
  const BagContents contents = mcap_contents(path);
  ASSERT_EQ(contents.topics.size(), 4u);
  std::map<std::string, std::uint64_t> counts;
  for (const BagTopic& topic : contents.topics)
    counts[topic.topic] = topic.messages;
  EXPECT_EQ(counts["/scan"], 10u);
  EXPECT_EQ(counts["/odom"], 10u);
  EXPECT_EQ(counts["/tf"], 10u);
  EXPECT_EQ(counts["/tf_static"], 1u);
  std::uint64_t visited = 0;
  read_mcap(
      path, [&](const BagTopic&, const BagMessageView& m) { visited += !m.data.empty(); }, nullptr);
  EXPECT_EQ(visited, 31u);
}

// ---- bad input: each error names the file, the byte and what was read before it ----

std::string read_bytes(const std::filesystem::path& path) {
  return test::read_file(path);
}

// Top-level records of an MCAP image: (opcode, offset).
std::vector<std::pair<int, std::size_t>> records_of(const std::string& bytes) {
  std::vector<std::pair<int, std::size_t>> out;
  for (std::size_t at = 8; at + 9 <= bytes.size();) {
    std::uint64_t length;
    std::memcpy(&length, bytes.data() + at + 1, 8);
    out.emplace_back(static_cast<unsigned char>(bytes[at]), at);
    if (bytes[at] == 0x02)
      break;
    at += 9 + length;
  }
  return out;
}

std::size_t first_record(const std::string& bytes, int opcode) {
  for (const auto& [op, at] : records_of(bytes))
    if (op == opcode)
      return at;
  ADD_FAILURE() << "no record of opcode " << opcode;
  return 0;
}

void expect_read_error(const std::filesystem::path& path, const std::vector<std::string>& parts) {
  std::vector<std::string> all = parts;
  all.push_back(path.string());
  all.push_back("at byte ");
  test::expect_input_error(
      [&] {
        read_mcap(
            path, [](const BagTopic&, const BagMessageView&) {}, nullptr);
      },
      all);
}

TEST(McapReaderErrors, TruncatedChunk) {
  const test::TempDir dir;
  const std::string bytes = read_bytes(kBags / "fr079_small.mcap");
  const std::size_t chunk = first_record(bytes, 0x06);
  const auto path = dir / "cut.mcap";
  test::write_file(path, bytes.substr(0, chunk + 200));
  expect_read_error(path, {"past the end of the file", "read before it: 0 messages"});
  test::expect_input_error([&] { mcap_contents(path); }, {path.string(), "at byte "});
}

TEST(McapReaderErrors, WrongCrc) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  FLOORGRID_REQUIRE_MCAP_WRITER();
  const test::TempDir dir;
  test::BagBytes written;
  const auto path = write_mcap(dir, records, "--compression none --chunk-size 20000", written);
  std::string bytes = read_bytes(path);
  const auto chunks = records_of(bytes);
  std::vector<std::size_t> chunk_offsets;
  for (const auto& [op, at] : chunks)
    if (op == 0x06)
      chunk_offsets.push_back(at);
  ASSERT_GE(chunk_offsets.size(), 2u);
  bytes[chunk_offsets[1] + 500] ^= 0x10;  // a byte of a message's data in the second chunk
  test::write_file(path, bytes);
  expect_read_error(
      path, {"wrong CRC", "at byte " + std::to_string(chunk_offsets[1]), "read before it: "});
}

TEST(McapReaderErrors, UnknownCompression) {
  const test::TempDir dir;
  std::string bytes = read_bytes(kBags / "fr079_small.mcap");
  const std::size_t chunk = first_record(bytes, 0x06);
  // Chunk content: three u64, a u32 CRC, then the compression string (u32 length, "lz4").
  const std::size_t name = chunk + 9 + 28 + 4;
  ASSERT_EQ(bytes.substr(name, 3), "lz4");
  bytes[name + 2] = '7';
  const auto path = dir / "lz7.mcap";
  test::write_file(path, bytes);
  expect_read_error(path, {"unknown compression", "lz7"});
}

TEST(McapReaderErrors, MessageOnAnUnknownChannel) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  FLOORGRID_REQUIRE_MCAP_WRITER();
  const test::TempDir dir;
  test::BagBytes written;
  const auto path = write_mcap(dir, records, "--no-chunks --no-summary", written);
  std::string bytes = read_bytes(path);
  std::size_t tenth = 0, seen = 0;
  for (const auto& [op, at] : records_of(bytes))
    if (op == 0x05 && ++seen == 10)
      tenth = at;
  ASSERT_GT(tenth, 0u);
  bytes[tenth + 9] = 0x77;  // channel_id
  test::write_file(path, bytes);
  expect_read_error(
      path, {"channel 119", "at byte " + std::to_string(tenth), "read before it: 9 messages"});
}

TEST(McapReaderErrors, NotAnMcapFile) {
  const test::TempDir dir;
  const auto path = dir / "log.mcap";
  test::write_file(path, "FLASER 3 1 2 3 0 0 0 0 0 0 1.0 host 1.0\n");
  expect_read_error(path, {"not an MCAP file"});
  test::expect_input_error([&] { mcap_contents(path); },
                           {path.string(), "at byte 0", "not an MCAP file"});
  const auto empty = dir / "empty.mcap";
  test::write_file(empty, "");
  expect_read_error(empty, {"not an MCAP file"});
}

TEST(McapReaderErrors, LyingLengthsAreCaughtBeforeAllocating) {
  const test::TempDir dir;
  std::string bytes = read_bytes(kBags / "fr079_small.mcap");
  const std::size_t chunk = first_record(bytes, 0x06);
  // The chunk's uncompressed_size (third u64 of its content) claims 2^62 bytes.
  const std::uint64_t huge = std::uint64_t{1} << 62;
  std::memcpy(bytes.data() + chunk + 9 + 16, &huge, 8);
  const auto path = dir / "huge.mcap";
  test::write_file(path, bytes);
  expect_read_error(path, {"which cannot be"});
  // A record length past the end of the file.
  bytes = read_bytes(kBags / "fr079_small.mcap");
  std::memcpy(bytes.data() + chunk + 1, &huge, 8);
  test::write_file(path, bytes);
  expect_read_error(path, {"reaches past the end of the file"});
  // A summary that lies: contents fall back to reading through, with a warning.
  bytes = read_bytes(kBags / "fr079_small.mcap");
  const std::size_t footer = bytes.size() - 8 - 29;
  std::memcpy(bytes.data() + footer + 9, &huge, 8);  // summary_start
  test::write_file(path, bytes);
  const BagContents contents = mcap_contents(path);
  EXPECT_EQ(contents.messages, 31u);
  ASSERT_FALSE(contents.warnings.empty());
  EXPECT_NE(contents.warnings[0].find("unusable"), std::string::npos) << contents.warnings[0];
}

}  // namespace
}  // namespace floorgrid::io
