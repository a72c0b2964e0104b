// The ROS 1 bag reader against bags written by an independent writer (Debian's python3-rosbag,
// tests/bags/write_ros1_bag.py) from 200 scans of fr079: topics, types, counts, times and the
// exact bytes of every message, for each chunk compression; then damaged copies of them.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/bag_file.hpp"
#include "tests/io/ros1_bag_test_support.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using namespace ros1_test;
using test::read_file;
using test::read_json;

/// Checks contents against the writer's manifest: topics, types, counts, times.
void expect_matches_manifest(const BagContents& contents, const nlohmann::json& manifest) {
  EXPECT_EQ(contents.format, BagFormat::ros1);
  EXPECT_EQ(contents.messages, manifest["messages"].get<std::uint64_t>());
  EXPECT_EQ(contents.start_ns, manifest["start_ns"].get<std::int64_t>());
  EXPECT_EQ(contents.end_ns, manifest["end_ns"].get<std::int64_t>());
  ASSERT_EQ(contents.topics.size(), manifest["topics"].size());
  for (const auto& [name, expected] : manifest["topics"].items()) {
    const BagTopic* topic = find_topic(contents, name);
    ASSERT_NE(topic, nullptr) << name;
    EXPECT_EQ(topic->type, expected["type"].get<std::string>()) << name;
    EXPECT_EQ(topic->encoding, MessageEncoding::ros1) << name;
    EXPECT_EQ(topic->messages, expected["messages"].get<std::uint64_t>()) << name;
    EXPECT_EQ(topic->first_ns, expected["first_ns"].get<std::int64_t>()) << name;
    EXPECT_EQ(topic->last_ns, expected["last_ns"].get<std::int64_t>()) << name;
  }
}

class Ros1BagCompression : public ::testing::TestWithParam<std::string> {};

TEST_P(Ros1BagCompression, ContentsFromTheIndexMatchTheWriter) {
  REQUIRE_ROS1_BAGS();
  const fs::path path = bag_with(GetParam());
  const BagContents contents = ros1_bag_contents(path);
  expect_matches_manifest(contents, read_json(path.string() + ".json"));
  EXPECT_TRUE(contents.warnings.empty()) << contents.warnings.front();
  EXPECT_EQ(contents.bytes, fs::file_size(path));
  ASSERT_EQ(contents.topics.size(), 4u);
  EXPECT_EQ(contents.topics[0].topic, "/tf_static");  // the container's order: first written
}

TEST_P(Ros1BagCompression, ReadsExactlyTheBytesWritten) {
  REQUIRE_ROS1_BAGS();
  const fs::path path = bag_with(GetParam());
  const nlohmann::json manifest = read_json(path.string() + ".json");
  BagContents contents;
  const std::map<std::string, std::string> bytes = read_bytes(path, &contents);
  expect_matches_manifest(contents, manifest);
  EXPECT_TRUE(contents.warnings.empty());
  for (const auto& [name, expected] : manifest["topics"].items()) {
    ASSERT_TRUE(bytes.contains(name)) << name;
    EXPECT_EQ(bytes.at(name).size(), expected["bytes"].get<std::size_t>()) << name;
    EXPECT_TRUE(bytes.at(name) == read_file(expected["dump"].get<std::string>()))
        << name << ": the bytes read differ from those written";
  }
}

TEST_P(Ros1BagCompression, VisitsInFileOrderWithTheConnectionsTopic) {
  REQUIRE_ROS1_BAGS();
  const fs::path path = bag_with(GetParam());
  const BagContents contents = ros1_bag_contents(path);
  std::vector<std::string> order;
  std::uint64_t last_offset = 0;
  bool offsets_increase = true;
  read_ros1_bag(
      path,
      [&](const BagTopic& topic, const BagMessageView& message) {
        EXPECT_EQ(message.topic_id, topic.id);
        const BagTopic* declared = find_topic(contents, topic.topic);
        ASSERT_NE(declared, nullptr);
        EXPECT_EQ(declared->id, topic.id);
        EXPECT_EQ(declared->type, topic.type);
        order.push_back(topic.topic);
        if (GetParam() == "none") {  // offsets are the file's only for uncompressed chunks
          offsets_increase = offsets_increase && message.offset > last_offset;
          last_offset = message.offset;
        }
      },
      nullptr);
  // The writer wrote /tf_static, then per pose /odom, /tf and the scan.
  ASSERT_EQ(order.size(), 601u);
  EXPECT_EQ(order[0], "/tf_static");
  EXPECT_EQ(order[1], "/odom");
  EXPECT_EQ(order[2], "/tf");
  EXPECT_EQ(order[3], "/scan");
  EXPECT_EQ(order[600], "/scan");
  EXPECT_TRUE(offsets_increase);
}

INSTANTIATE_TEST_SUITE_P(Ros1Bag, Ros1BagCompression, ::testing::Values("none", "bz2", "lz4"));

TEST(Ros1BagTest, VisitsOnlyTheTopicsAskedFor) {
  REQUIRE_ROS1_BAGS();
  const fs::path path = bag_with("lz4");
  const std::set<std::string> wanted = {"/scan", "/tf"};
  BagContents contents;
  const std::map<std::string, std::string> bytes = read_bytes(path, &contents, &wanted);
  EXPECT_EQ(bytes.size(), 2u);
  EXPECT_TRUE(bytes.contains("/scan") && bytes.contains("/tf"));
  EXPECT_EQ(contents.messages, 601u);  // all are still counted
}

TEST(Ros1BagTest, BagWithoutOdomHasOnlyTf) {
  REQUIRE_ROS1_BAGS();
  const fs::path path = bags().bag("no_odom", "--compression lz4 --no-odom");
  const BagContents contents = ros1_bag_contents(path);
  expect_matches_manifest(contents, read_json(path.string() + ".json"));
  EXPECT_EQ(find_topic(contents, "/odom"), nullptr);
  ASSERT_NE(find_topic(contents, "/tf"), nullptr);
  EXPECT_EQ(find_topic(contents, "/tf")->messages, 200u);
}

TEST(Ros1BagTest, ReadsTheCommittedFixture) {
  const fs::path path = kSource / "tests/bags/fr079_5scans_lz4.bag";
  const nlohmann::json manifest = read_json(path.string() + ".json");
  expect_matches_manifest(ros1_bag_contents(path), manifest);
  BagContents contents;
  const std::map<std::string, std::string> bytes = read_bytes(path, &contents);
  expect_matches_manifest(contents, manifest);
  for (const auto& [name, expected] : manifest["topics"].items())
    EXPECT_EQ(bytes.at(name).size(), expected["bytes"].get<std::size_t>()) << name;
}

}  // namespace
}  // namespace floorgrid::io
