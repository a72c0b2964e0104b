#pragma once

// What the ROS 1 bag tests share: bags written once per test run by the independent writer
// (tests/bags/write_ros1_bag.py, Debian's python3-rosbag) from 200 scans of fr079.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "floorgrid/io/logs/bag_file.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io::ros1_test {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::run_command;
using test::TempDir;

inline const fs::path kSource = FLOORGRID_SOURCE_DIR;
inline const std::string kPython = "/usr/bin/python3";

/// Bags written once for the whole suite, in one temporary folder.
class Ros1Bags {
 public:
  /// Why the bags cannot be made (python3-rosbag or the data missing), or empty.
  std::string unavailable;

  Ros1Bags() {
    const fs::path log = test::data_path("fr079/freiburg-079-corrected.log.gz");
    if (!fs::exists(log)) {
      unavailable = "shared data missing: " + log.string();
      return;
    }
    const test::CommandResult import =
        run_command(kPython + " -c 'import rosbag, sensor_msgs.msg, nav_msgs.msg, tf2_msgs.msg'");
    if (import.status != 0) {
      unavailable = "python3-rosbag is not importable by " + kPython + ": " + import.err;
      return;
    }
    records_ = dir_ / "fr079.jsonl";
    const test::CommandResult made =
        run_command(kPython + " " + quoted(kSource / "tests/bags/carmen_to_records.py") + " " +
                    quoted(log) + " " + quoted(records_) + " --max-scans 200");
    if (made.status != 0)
      unavailable = "carmen_to_records.py failed: " + made.err;
  }

  /// The bag written with `options` (made on first use), e.g. "--compression lz4".
  fs::path bag(const std::string& name, const std::string& options) {
    const fs::path path = dir_ / (name + ".bag");
    if (!fs::exists(path)) {
      const test::CommandResult made =
          run_command(kPython + " " + quoted(kSource / "tests/bags/write_ros1_bag.py") + " " +
                      quoted(records_) + " " + quoted(path) + " --dump " + options);
      EXPECT_EQ(made.status, 0) << made.err;
    }
    return path;
  }

 private:
  TempDir dir_;
  fs::path records_;
};

inline Ros1Bags& bags() {
  static Ros1Bags instance;
  return instance;
}

#define REQUIRE_ROS1_BAGS()                                           \
  do {                                                                \
    if (!::floorgrid::io::ros1_test::bags().unavailable.empty())      \
      GTEST_SKIP() << ::floorgrid::io::ros1_test::bags().unavailable; \
  } while (0)

// The first bags have chunks of 64 KB: several chunks, each holding every topic.
inline fs::path bag_with(const std::string& compression) {
  return bags().bag(compression, "--compression " + compression + " --chunk-threshold 65536");
}

/// Each topic's messages concatenated, as read.
inline std::map<std::string, std::string> read_bytes(
    const fs::path& path, BagContents* contents = nullptr,
    const std::set<std::string>* topics = nullptr) {
  std::map<std::string, std::string> bytes;
  const BagContents read = read_ros1_bag(
      path,
      [&](const BagTopic& topic, const BagMessageView& message) {
        bytes[topic.topic].append(reinterpret_cast<const char*>(message.data.data()),
                                  message.data.size());
      },
      topics);
  if (contents != nullptr)
    *contents = read;
  return bytes;
}

inline const BagTopic* find_topic(const BagContents& contents, const std::string& name) {
  for (const BagTopic& topic : contents.topics)
    if (topic.topic == name)
      return &topic;
  return nullptr;
}

}  // namespace floorgrid::io::ros1_test
