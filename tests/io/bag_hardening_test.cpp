// Bags that lie or hold what no run holds (issue 31): decompression bombs that state their size
// honestly, NaN and absurd values in the messages a run uses, a ROS 1 chunk without a
// compression name, a channel or connection defined twice, a long /tf_static chain. Each was
// read as something else before: gigabytes allocated, NaN read as a number, a guess.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/bag_log.hpp"
#include "tests/support/bag_writers.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

namespace fs = std::filesystem;
using test::expect_input_error;
using test::quoted;
using test::TempDir;

const fs::path kSource = FLOORGRID_SOURCE_DIR;

// ---- bytes laid out as the formats define them (independent of the readers) ----

std::string u16(std::uint16_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 2);
}
std::string u32(std::uint32_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 4);
}
std::string u64(std::uint64_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 8);
}

/// A ROS 1 header field "name=value" with its length.
std::string ros1_field(const std::string& name, const std::string& value) {
  return u32(static_cast<std::uint32_t>(name.size() + 1 + value.size())) + name + "=" + value;
}
/// A ROS 1 record: header length, header, data length, data.
std::string ros1_record(const std::string& header, const std::string& data) {
  return u32(static_cast<std::uint32_t>(header.size())) + header +
         u32(static_cast<std::uint32_t>(data.size())) + data;
}
std::string ros1_connection(std::uint32_t id, const std::string& topic, const std::string& type) {
  const std::string data = ros1_field("topic", topic) + ros1_field("type", type) +
                           ros1_field("md5sum", "992ce8a1687cec8c8bd883ec73ca41d1") +
                           ros1_field("message_definition", "string data\n");
  return ros1_record(
      ros1_field("op", "\x07") + ros1_field("conn", u32(id)) + ros1_field("topic", topic), data);
}
std::string ros1_message(std::uint32_t conn, std::uint32_t sec) {
  return ros1_record(ros1_field("op", "\x02") + ros1_field("conn", u32(conn)) +
                         ros1_field("time", u32(sec) + u32(5)),
                     u32(5) + "hello");
}
/// A ROS 1 bag without index: the magic, the bag header and one chunk of `records`, uncompressed
/// but named `compression`.
std::string ros1_bag(const std::string& compression, const std::string& records) {
  const std::string header =
      ros1_record(ros1_field("op", "\x03") + ros1_field("index_pos", u64(0)) +
                      ros1_field("conn_count", u32(1)) + ros1_field("chunk_count", u32(1)),
                  "");
  const std::string chunk =
      ros1_record(ros1_field("op", "\x05") + ros1_field("compression", compression) +
                      ros1_field("size", u32(static_cast<std::uint32_t>(records.size()))),
                  records);
  return "#ROSBAG V2.0\n" + header + chunk;
}

std::string mcap_string(const std::string& s) {
  return u32(static_cast<std::uint32_t>(s.size())) + s;
}
std::string mcap_record(std::uint8_t opcode, const std::string& content) {
  return std::string(1, static_cast<char>(opcode)) + u64(content.size()) + content;
}
std::string mcap_schema(std::uint16_t id, const std::string& name) {
  return mcap_record(3, u16(id) + mcap_string(name) + mcap_string("ros2msg") + u32(0));
}
std::string mcap_channel(std::uint16_t id, const std::string& topic) {
  return mcap_record(4, u16(id) + u16(1) + mcap_string(topic) + mcap_string("cdr") + u32(0));
}
std::string mcap_message(std::uint16_t channel, std::uint64_t time) {
  return mcap_record(5, u16(channel) + u32(0) + u64(time) + u64(time) + std::string("\0\1\0\0", 4));
}
/// An MCAP file of `body` (records of the data section), without summary.
std::string mcap_file(const std::string& body) {
  const std::string magic("\x89MCAP0\r\n", 8);
  return magic + mcap_record(1, mcap_string("ros2") + mcap_string("test")) + body +
         mcap_record(15, u32(0)) + mcap_record(2, u64(0) + u64(0) + u32(0)) + magic;
}

/// A zstd frame of `prefix` then `zeros` zero bytes that states its content size: a raw block,
/// then RLE blocks of 128 KiB (4 bytes each: the honest bomb's way to 32768x).
std::string zstd_frame(const std::string& prefix, std::uint64_t zeros) {
  std::string frame = u32(0xFD2FB528) + std::string(1, '\xE0') + u64(prefix.size() + zeros);
  const auto block = [&](bool last, int kind, std::uint32_t size, const std::string& payload) {
    const std::uint32_t header =
        (last ? 1u : 0u) | (static_cast<std::uint32_t>(kind) << 1) | (size << 3);
    frame += u32(header).substr(0, 3) + payload;
  };
  block(zeros == 0, 0, static_cast<std::uint32_t>(prefix.size()), prefix);
  constexpr std::uint64_t kBlock = 1 << 17;
  while (zeros > 0) {
    const std::uint64_t n = std::min(kBlock, zeros);
    zeros -= n;
    block(zeros == 0, 1, static_cast<std::uint32_t>(n), std::string(1, '\0'));
  }
  return frame;
}

/// An MCAP file whose one chunk is zstd of a schema, a channel and a message, then zeros, to
/// `size` bytes in all, stating that size.
std::string mcap_zstd_bomb(std::uint64_t size) {
  const std::string inner = mcap_schema(1, "sensor_msgs/msg/LaserScan") + mcap_channel(1, "/scan") +
                            mcap_message(1, 1000);
  const std::string frame = zstd_frame(inner, size - inner.size());
  return mcap_file(mcap_record(6, u64(1000) + u64(1000) + u64(size) + u32(0) + mcap_string("zstd") +
                                      u64(frame.size()) + frame));
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- decompression bombs (defect 4) ----

TEST(BagBombs, AnMcapZstdChunkStatingGigabytesIsRefusedBeforeItIsDecompressed) {
  // 3 GB of zeros in 92 KB, its size stated honestly in the chunk and in the zstd frame: before
  // the limit, reading it allocated 3.09 GB (the check was only 32768x the compressed size).
  TempDir dir;
  const std::string bytes = mcap_zstd_bomb(3'000'000'000ull);
  ASSERT_LT(bytes.size(), 100'000u);
  test::write_file(dir / "bomb.mcap", bytes);
  const std::size_t chunk_offset = 8 + 9 + 16;  // the magic, the Header record, then the chunk
  const auto start = std::chrono::steady_clock::now();
  for (const bool contents : {true, false}) {
    expect_input_error(
        [&] {
          if (contents)
            mcap_contents(dir / "bomb.mcap");
          else
            read_mcap(
                dir / "bomb.mcap", [](const BagTopic&, const BagMessageView&) {}, nullptr);
        },
        {"bomb.mcap", "at byte " + std::to_string(chunk_offset), "3000000000", "a chunk may take"});
  }
  EXPECT_LT(seconds_since(start), 5.0);
}

TEST(BagBombs, ARos1Bz2ChunkStatingGigabytesIsRefusedBeforeItIsDecompressed) {
  // fuzz/regressions/ros1_bag-bz2-bomb-4g.bag (fuzz/make_bombs.py): 3 KB whose bz2 chunk
  // honestly holds 4e9 bytes. Before the limit, reading it counted the bytes (34 s for 4 GB),
  // then allocated them and decompressed again.
  const fs::path bomb = kSource / "fuzz/regressions/ros1_bag-bz2-bomb-4g.bag";
  ASSERT_TRUE(fs::exists(bomb));
  const std::string bytes = test::read_file(bomb);
  const std::size_t chunk_offset = bytes.find("compression=bz2") - 4 - 4 - 4 - 4;
  const auto start = std::chrono::steady_clock::now();
  expect_input_error([&] { bag_contents(bomb); },
                     {"at byte", "4000000000", "a chunk may take", "read before it"});
  EXPECT_LT(seconds_since(start), 5.0);
  // The error names the chunk's own offset (its record's header length comes first).
  try {
    bag_contents(bomb);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at byte " + std::to_string(chunk_offset)),
              std::string::npos)
        << e.what();
  }
}

// ---- the containers' own fields (defect 14) ----

TEST(BagContainers, ARos1ChunkWithoutACompressionNameIsRefused) {
  // rosbag names every chunk's compression ("none" when there is none): "" was read as none.
  TempDir dir;
  const std::string records =
      ros1_connection(0, "/chatter", "std_msgs/String") + ros1_message(0, 100);
  test::write_file(dir / "named.bag", ros1_bag("none", records));
  EXPECT_EQ(bag_contents(dir / "named.bag").messages, 1u);
  test::write_file(dir / "unnamed.bag", ros1_bag("", records));
  expect_input_error([&] { bag_contents(dir / "unnamed.bag"); },
                     {"unnamed.bag", "at byte", "unknown compression ''", "none, bz2, lz4"});
}

TEST(BagContainers, ARos1ConnectionDeclaredAgainAsAnotherTopicIsRefused) {
  TempDir dir;
  // rosbag writes each connection twice, alike: that is fine.
  const std::string same = ros1_connection(0, "/chatter", "std_msgs/String") +
                           ros1_connection(0, "/chatter", "std_msgs/String") + ros1_message(0, 100);
  test::write_file(dir / "same.bag", ros1_bag("none", same));
  EXPECT_EQ(bag_contents(dir / "same.bag").messages, 1u);
  const std::string other = ros1_connection(0, "/chatter", "std_msgs/String") +
                            ros1_connection(0, "/odom", "nav_msgs/Odometry") + ros1_message(0, 100);
  test::write_file(dir / "other.bag", ros1_bag("none", other));
  expect_input_error([&] { bag_contents(dir / "other.bag"); },
                     {"other.bag", "at byte", "connection 0 is declared again", "/odom"});
}

TEST(BagContainers, AnMcapChannelDefinedAgainAsAnotherTopicIsRefused) {
  TempDir dir;
  const std::string schema = mcap_schema(1, "sensor_msgs/msg/LaserScan");
  // Writers repeat a channel record alike (in chunks, in the summary): that is fine.
  test::write_file(dir / "same.mcap", mcap_file(schema + mcap_channel(1, "/scan") +
                                                mcap_channel(1, "/scan") + mcap_message(1, 5)));
  EXPECT_EQ(mcap_contents(dir / "same.mcap").messages, 1u);
  // Channel 1 redefined as /odom: its messages would be counted on /scan, read as scans.
  const std::string first = mcap_channel(1, "/scan");
  const std::string body = schema + first + mcap_channel(1, "/odom") + mcap_message(1, 5);
  test::write_file(dir / "other.mcap", mcap_file(body));
  const std::size_t second_offset = 8 + 9 + 16 + schema.size() + first.size();
  for (const bool contents : {true, false}) {
    expect_input_error(
        [&] {
          if (contents)
            mcap_contents(dir / "other.mcap");
          else
            read_mcap(
                dir / "other.mcap", [](const BagTopic&, const BagMessageView&) {}, nullptr);
        },
        {"other.mcap", "at byte " + std::to_string(second_offset), "channel 1", "/odom"});
  }
}

// ---- values of the messages a run uses (defect 5, and odometry at 1e300 of defect 14) ----

/// fr079's first scans as a ROS 1 bag written by tests/bags/write_ros1_bag.py after `edit` has
/// changed the records (carmen_to_records.py's JSON lines). A number set to the text "NaN" or
/// "Infinity" is written as that JSON token (Python reads it as the float).
class EditedBags : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    records_ = test::bag_records(why);
    if (records_.empty())
      GTEST_SKIP() << why;
    if (test::run_command("/usr/bin/python3 -c 'import rosbag'").status != 0)
      GTEST_SKIP() << "python3-rosbag is not importable by /usr/bin/python3";
  }

  fs::path bag(const std::string& name,
               const std::function<void(nlohmann::json&, std::size_t)>& edit,
               const std::string& options = "") {
    std::ifstream in(records_);
    std::string line, text;
    std::size_t index = 0;
    while (std::getline(in, line)) {
      if (line.empty())
        continue;
      nlohmann::json record = nlohmann::json::parse(line);
      edit(record, index++);
      std::string dumped = record.dump();
      for (const std::string token : {"NaN", "Infinity", "-Infinity"}) {
        const std::string quoted_token = "\"" + token + "\"";
        for (std::size_t at; (at = dumped.find(quoted_token)) != std::string::npos;)
          dumped.replace(at, quoted_token.size(), token);
      }
      text += dumped + "\n";
    }
    const fs::path jsonl = dir_ / (name + ".jsonl");
    test::write_file(jsonl, text);
    const fs::path out = dir_ / (name + ".bag");
    const test::CommandResult r =
        test::run_command("/usr/bin/python3 " + quoted(kSource / "tests/bags/write_ros1_bag.py") +
                          " " + quoted(jsonl) + " " + quoted(out) + " " + options);
    EXPECT_EQ(r.status, 0) << r.err;
    return out;
  }

  /// Sets `key` of the `nth` record of `kind` (0-based) to `value`.
  static std::function<void(nlohmann::json&, std::size_t)> set_nth(const std::string& kind,
                                                                   std::size_t nth,
                                                                   const std::string& key,
                                                                   nlohmann::json value) {
    auto seen = std::make_shared<std::size_t>(0);
    return [=](nlohmann::json& record, std::size_t) {
      if (record["kind"] == kind && (*seen)++ == nth)
        record[key] = value;
    };
  }

  TempDir dir_;
  fs::path records_;
};

TEST_F(EditedBags, ANanOdometryQuaternionIsRefusedNamingTopicMessageAndField) {
  // Was read as heading 0 without a word; align then exited 0 with cv_m 0 (truth error 1.26 m).
  const fs::path b = bag("odom_q_nan", set_nth("pose", 4, "yaw", "NaN"));
  expect_input_error([&] { read_bag_log(b); },
                     {"odom_q_nan.bag", "topic /odom, message 5", "pose.pose.orientation",
                      "must be a finite number", "nan"});
}

TEST_F(EditedBags, NanOrAbsurdOdometryPositionsAreRefused) {
  const fs::path nan = bag("odom_x_nan", set_nth("pose", 2, "x", "NaN"));
  expect_input_error([&] { read_bag_log(nan); },
                     {"topic /odom, message 3", "pose.pose.position.x", "nan"});
  const fs::path huge = bag("odom_x_huge", set_nth("pose", 0, "y", 1e300));
  expect_input_error([&] { read_bag_log(huge); },
                     {"topic /odom, message 1", "pose.pose.position.y", "within 1e+07", "1e+300"});
}

TEST_F(EditedBags, TheOdometryOnTfIsCheckedToo) {
  // Without /odom the run's odometry is the odom -> base_link transforms on /tf.
  const fs::path b = bag("tf_x_nan", set_nth("pose", 3, "x", "NaN"), "--no-odom");
  expect_input_error([&] { read_bag_log(b); },
                     {"topic /tf, message 4", "transforms[0].transform.translation.x", "nan"});
}

TEST_F(EditedBags, NanOrInfiniteAngleIncrementsAreRefusedNamingTheScan) {
  // Were accepted by info; align then blamed initial_pose.
  const fs::path nan = bag("inc_nan", set_nth("scan", 7, "angle_increment", "NaN"));
  expect_input_error([&] { read_bag_log(nan); },
                     {"inc_nan.bag", "topic /scan, message 8", "angle_increment", "nan"});
  const fs::path inf = bag("inc_inf", set_nth("scan", 0, "angle_increment", "Infinity"));
  expect_input_error([&] { read_bag_log(inf); },
                     {"topic /scan, message 1", "angle_increment", "inf"});
  // dataset.yaml's laser: gives the angles: the message's are not used, so not refused.
  BagLogOptions given;
  given.laser.start_angle = -1.5707963267948966;
  given.laser.angle_increment = 0.008726646259971648;
  EXPECT_FALSE(read_bag_log(inf, given).scans.empty());
}

TEST_F(EditedBags, ANanLaserMountIsRefusedNamingTfStatic) {
  const fs::path b = bag(
      "static_nan", [](nlohmann::json&, std::size_t) {}, "--mount nan,0,0");
  expect_input_error([&] { read_bag_log(b); }, {"static_nan.bag", "topic /tf_static, message 1",
                                                "transforms[0].transform.translation.x", "nan"});
}

TEST_F(EditedBags, ALaserMountedThroughALongTfStaticChainIsFound) {
  // 5000 links base_link -> link1 -> ... -> laser: was "no transform" (the walk stopped at 64),
  // the laser then taken to sit at base_link.
  const fs::path one = bag(
      "chain1", [](nlohmann::json&, std::size_t) {}, "--mount 0.2,-0.1,0.3");
  const fs::path chain = bag(
      "chain5000", [](nlohmann::json&, std::size_t) {}, "--mount 0.2,-0.1,0.3 --mount-chain 5000");
  const BagLog direct = read_bag_log(one);
  const BagLog chained = read_bag_log(chain);
  EXPECT_NEAR(direct.laser_mount.x, 0.2, 1e-12);
  EXPECT_NEAR(chained.laser_mount.x, 0.2, 1e-9);
  EXPECT_NEAR(chained.laser_mount.y, -0.1, 1e-9);
  EXPECT_NEAR(chained.laser_mount.theta, 0.3, 1e-9);
  for (const std::string& warning : chained.summary.warnings)
    EXPECT_EQ(warning.find("no transform"), std::string::npos) << warning;
}

}  // namespace
}  // namespace floorgrid::io
