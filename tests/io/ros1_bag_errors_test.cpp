// The ROS 1 bag reader on damaged copies of bags written by python3-rosbag: every error names
// the file, the byte offset and what was read before it; a bag without index is read through.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/bag_file.hpp"
#include "tests/io/ros1_bag_test_support.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using namespace ros1_test;
using test::expect_input_error;
using test::read_file;
using test::read_json;
using test::TempDir;
using test::write_file;

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

void put_u32(std::string& bytes, std::size_t offset, std::uint32_t value) {
  std::memcpy(bytes.data() + offset, &value, 4);
}

/// A top-level record as the test finds it (a few lines of the format, independent of the reader).
struct TopRecord {
  std::size_t offset = 0;
  std::uint8_t op = 0;
  std::size_t data_offset = 0;
  std::uint32_t data_len = 0;
};

std::vector<TopRecord> top_records(const std::string& bytes) {
  std::vector<TopRecord> records;
  for (std::size_t offset = 13; offset + 4 <= bytes.size();) {
    TopRecord r;
    r.offset = offset;
    const std::uint32_t header_len = u32_at(bytes, offset);
    for (std::size_t f = offset + 4; f < offset + 4 + header_len;) {
      const std::uint32_t field_len = u32_at(bytes, f);
      if (bytes.compare(f + 4, 3, "op=") == 0)
        r.op = static_cast<std::uint8_t>(bytes[f + 7]);
      f += 4 + field_len;
    }
    r.data_len = u32_at(bytes, offset + 4 + header_len);
    r.data_offset = offset + 8 + header_len;
    records.push_back(r);
    offset = r.data_offset + r.data_len;
  }
  return records;
}

std::vector<TopRecord> chunks_of(const std::string& bytes) {
  std::vector<TopRecord> chunks;
  for (const TopRecord& r : top_records(bytes))
    if (r.op == 0x05)
      chunks.push_back(r);
  return chunks;
}

/// Where the value of the first field `name=` at or after `from` starts.
std::size_t field_value(const std::string& bytes, const std::string& name, std::size_t from = 0) {
  const std::size_t at = bytes.find(name + "=", from);
  EXPECT_NE(at, std::string::npos) << name;
  return at + name.size() + 1;
}

/// A damaged copy of a bag in a folder of the test.
class Ros1BagErrors : public ::testing::Test {
 protected:
  fs::path damaged(const fs::path& bag, const std::string& bytes) {
    const fs::path path = dir_ / ("damaged-" + bag.filename().string());
    write_file(path, bytes);
    return path;
  }
  static void read_all(const fs::path& path) {
    read_ros1_bag(
        path, [](const BagTopic&, const BagMessageView&) {}, nullptr);
  }
  TempDir dir_;
};

TEST_F(Ros1BagErrors, TruncatedChunkNamesTheChunkAndWhatWasReadBefore) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("none");
  const std::string bytes = read_file(bag);
  const std::vector<TopRecord> chunks = chunks_of(bytes);
  ASSERT_GE(chunks.size(), 3u);
  const fs::path cut = damaged(bag, bytes.substr(0, chunks[1].data_offset + 1000));
  const std::vector<std::string> parts = {cut.string(),
                                          "at byte " + std::to_string(chunks[1].offset),
                                          "truncated", "read before it: ", " on 4 topics"};
  expect_input_error([&] { read_all(cut); }, parts);
  // Its index_pos now lies past the end: read through, which meets the same cut.
  expect_input_error([&] { ros1_bag_contents(cut); }, parts);
}

TEST_F(Ros1BagErrors, LyingChunkLengthIsAnErrorNotAnAllocation) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("lz4");
  std::string bytes = read_file(bag);
  const TopRecord chunk = chunks_of(bytes).at(0);
  put_u32(bytes, chunk.data_offset - 4, 0xfffffff0u);
  const fs::path path = damaged(bag, bytes);
  expect_input_error([&] { read_all(path); },
                     {path.string(), "at byte " + std::to_string(chunk.offset), "runs past the end",
                      "read before it: 0 messages on 0 topics"});
}

TEST_F(Ros1BagErrors, LyingUncompressedSizeIsAnError) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("lz4");
  std::string bytes = read_file(bag);
  const TopRecord chunk = chunks_of(bytes).at(0);
  put_u32(bytes, field_value(bytes, "size", chunk.offset), 0xfffffff0u);
  const fs::path path = damaged(bag, bytes);
  expect_input_error([&] { read_all(path); },
                     {path.string(), "at byte " + std::to_string(chunk.offset), "claims"});
}

TEST_F(Ros1BagErrors, CorruptRecordLengthInsideAChunk) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("none");
  std::string bytes = read_file(bag);
  const TopRecord chunk = chunks_of(bytes).at(1);
  put_u32(bytes, chunk.data_offset, 0x00ffffffu);  // its first record's header length
  const fs::path path = damaged(bag, bytes);
  expect_input_error(
      [&] { read_all(path); },
      {path.string(), "at byte " + std::to_string(chunk.data_offset),
       "header of 16777215 bytes runs past the end of its chunk", "read before it: "});
}

TEST_F(Ros1BagErrors, UnknownCompression) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("lz4");
  std::string bytes = read_file(bag);
  const TopRecord chunk = chunks_of(bytes).at(0);
  for (std::size_t at = 0; (at = bytes.find("compression=lz4", at)) != std::string::npos;)
    bytes.replace(at, 15, "compression=xz4");
  const fs::path path = damaged(bag, bytes);
  expect_input_error([&] { read_all(path); },
                     {path.string(), "at byte " + std::to_string(chunk.offset),
                      "unknown compression 'xz4'", "read before it: 0 messages"});
}

TEST_F(Ros1BagErrors, MessageOnAnUndeclaredConnection) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("none");
  std::string bytes = read_file(bag);
  const std::size_t message = bytes.find(std::string("op=\x02", 4), chunks_of(bytes).at(0).offset);
  ASSERT_NE(message, std::string::npos);
  put_u32(bytes, field_value(bytes, "conn", message), 99);
  const fs::path path = damaged(bag, bytes);
  expect_input_error([&] { read_all(path); },
                     {path.string(), "at byte ", "connection 99", "no connection record declares",
                      "read before it: 0 messages"});
}

TEST_F(Ros1BagErrors, NotABag) {
  const fs::path path = dir_ / "notes.bag";
  write_file(path, "#ROSBAG V1.2\nold\n");
  expect_input_error([&] { ros1_bag_contents(path); },
                     {path.string(), "at byte 0", "not a ROS 1 bag of format 2.0"});
  const fs::path empty = dir_ / "empty.bag";
  write_file(empty, "");
  expect_input_error([&] { read_all(empty); }, {empty.string(), "at byte 0"});
}

TEST_F(Ros1BagErrors, BagWithoutIndexIsReadThroughWithAWarning) {
  REQUIRE_ROS1_BAGS();
  for (const std::string compression : {"none", "lz4"}) {
    const fs::path bag = bag_with(compression);
    const nlohmann::json manifest = read_json(bag.string() + ".json");
    std::string bytes = read_file(bag);
    const std::size_t index_pos = field_value(bytes, "index_pos");
    std::memset(bytes.data() + index_pos, 0, 8);
    const fs::path path = damaged(bag, bytes);
    const BagContents contents = ros1_bag_contents(path);
    ASSERT_FALSE(contents.warnings.empty()) << compression;
    EXPECT_NE(contents.warnings[0].find("no index"), std::string::npos) << contents.warnings[0];
    EXPECT_EQ(contents.messages, manifest["messages"].get<std::uint64_t>());
    EXPECT_EQ(contents.topics.size(), 4u);
    BagContents read;
    const std::map<std::string, std::string> got = read_bytes(path, &read);
    EXPECT_FALSE(read.warnings.empty());
    for (const auto& [name, expected] : manifest["topics"].items())
      EXPECT_TRUE(got.at(name) == read_file(expected["dump"].get<std::string>())) << name;
  }
}

TEST_F(Ros1BagErrors, BrokenIndexFallsBackToReadingThrough) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bag_with("bz2");
  std::string bytes = read_file(bag);
  // index_pos pointing into the second chunk's data: the index section is garbage.
  const std::uint64_t wrong = chunks_of(bytes).at(1).data_offset + 7;
  std::memcpy(bytes.data() + field_value(bytes, "index_pos"), &wrong, 8);
  const fs::path path = damaged(bag, bytes);
  const BagContents contents = ros1_bag_contents(path);
  ASSERT_FALSE(contents.warnings.empty());
  EXPECT_NE(contents.warnings[0].find("index is broken"), std::string::npos)
      << contents.warnings[0];
  EXPECT_NE(contents.warnings[0].find("at byte"), std::string::npos) << contents.warnings[0];
  EXPECT_EQ(contents.messages, 601u);
}

TEST_F(Ros1BagErrors, RecordingCutOffIsReadUpToTheCut) {
  REQUIRE_ROS1_BAGS();
  // A recording killed mid-chunk: no index (index_pos 0) and the file ends inside a chunk.
  const fs::path bag = bag_with("none");
  std::string bytes = read_file(bag);
  std::memset(bytes.data() + field_value(bytes, "index_pos"), 0, 8);
  const TopRecord chunk = chunks_of(bytes).at(2);
  const fs::path path = damaged(bag, bytes.substr(0, chunk.data_offset + 500));
  BagContents read;
  read_bytes(path, &read);
  EXPECT_GT(read.messages, 0u);
  EXPECT_LT(read.messages, 601u);
  ASSERT_EQ(read.warnings.size(), 2u);
  EXPECT_NE(read.warnings[1].find("cut off"), std::string::npos) << read.warnings[1];
  const BagContents contents = ros1_bag_contents(path);
  EXPECT_EQ(contents.messages, read.messages);
}

}  // namespace
}  // namespace floorgrid::io
