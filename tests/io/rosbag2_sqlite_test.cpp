// The rosbag2 sqlite3 reader against bags of an independent writer
// (tests/bags/write_rosbag2_db3.py: Python's sqlite3 and a CDR encoder of its own) holding fr079
// as ROS 2 messages.
#include <gtest/gtest.h>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/rosbag2_folder.hpp"
#include "tests/support/bag_writers.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::quoted;

const std::filesystem::path kBags = std::filesystem::path(FLOORGRID_SOURCE_DIR) / "tests/bags";

std::filesystem::path write_bag(const test::TempDir& dir, const std::filesystem::path& records,
                                const std::string& options, test::BagBytes& written) {
  const std::filesystem::path out = dir / "bag";
  written = test::run_writer("/usr/bin/python3 " + quoted(kBags / "write_rosbag2_db3.py") + " " +
                                 quoted(records) + " " + quoted(out) + " " + options,
                             dir.path());
  return out;
}

TEST(Rosbag2Sqlite, FolderAndFileGiveWhatTheWriterWrote) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  const test::TempDir dir;
  test::BagBytes written;
  const auto folder = write_bag(dir, records, "", written);
  ASSERT_EQ(written.at("/scan").count, 120u);
  EXPECT_EQ(rosbag2_folder_format(folder), BagFormat::rosbag2_sqlite);
  for (const std::filesystem::path& path : {folder, folder / "bag_0.db3"}) {
    SCOPED_TRACE(path.string());
    const BagContents contents = rosbag2_sqlite_contents(path);
    EXPECT_EQ(contents.format, BagFormat::rosbag2_sqlite);
    EXPECT_TRUE(contents.warnings.empty());
    test::expect_contents(written, contents);
    BagContents counted;
    test::expect_same(written, test::read_all(path, &read_rosbag2_sqlite, &counted));
    test::expect_contents(written, counted);
    EXPECT_EQ(counted.start_ns, contents.start_ns);
    EXPECT_EQ(counted.end_ns, contents.end_ns);
  }
}

TEST(Rosbag2Sqlite, SplitBagIsReadAsOne) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  const test::TempDir dir;
  test::BagBytes written;
  const auto folder = write_bag(dir, records, "--split-every 100 --no-odom", written);
  ASSERT_TRUE(std::filesystem::exists(folder / "bag_2.db3"));
  const BagContents contents = rosbag2_sqlite_contents(folder);
  test::expect_contents(written, contents);
  test::expect_same(written, test::read_all(folder, &read_rosbag2_sqlite));
}

TEST(Rosbag2Sqlite, VisitsOnlyTheTopicsAskedFor) {
  const std::set<std::string> wanted = {"/tf"};
  std::uint64_t visited = 0;
  const BagContents counted = read_rosbag2_sqlite(
      kBags / "fr079_small_db3",
      [&](const BagTopic& topic, const BagMessageView& message) {
        EXPECT_EQ(topic.topic, "/tf");
        EXPECT_EQ(message.offset, 0u);
        ++visited;
      },
      &wanted);
  EXPECT_EQ(visited, 10u);
  EXPECT_EQ(counted.messages, 31u);
}

TEST(Rosbag2Sqlite, ReadsTheCommittedSmallBag) {
  const BagContents contents = rosbag2_sqlite_contents(kBags / "fr079_small_db3");
  ASSERT_EQ(contents.topics.size(), 4u);
  EXPECT_EQ(contents.messages, 31u);
  for (const BagTopic& topic : contents.topics) {
    if (topic.topic == "/scan") {
      EXPECT_EQ(topic.type, "sensor_msgs/msg/LaserScan");
    }
  }
}

TEST(Rosbag2SqliteErrors, NotASqliteFile) {
  const test::TempDir dir;
  const auto path = dir / "bag.db3";
  test::write_file(path, "rosbag2 but not really\n");
  test::expect_input_error([&] { rosbag2_sqlite_contents(path); }, {path.string()});
  test::expect_input_error(
      [&] {
        read_rosbag2_sqlite(
            path, [](const BagTopic&, const BagMessageView&) {}, nullptr);
      },
      {path.string()});
  test::expect_input_error([&] { rosbag2_sqlite_contents(dir / "missing.db3"); }, {"missing.db3"});
}

TEST(Rosbag2SqliteErrors, SqliteWithoutTheTables) {
  const test::TempDir dir;
  const auto path = dir / "other.db3";
  const auto r = test::run_command(
      "/usr/bin/python3 -c \"import sqlite3,sys; d=sqlite3.connect(sys.argv[1]); "
      "d.execute('CREATE TABLE topics(id INTEGER, name TEXT)'); d.commit()\" " +
      quoted(path));
  ASSERT_EQ(r.status, 0) << r.err;
  test::expect_input_error([&] { rosbag2_sqlite_contents(path); }, {path.string(), "type"});
  test::expect_input_error(
      [&] {
        read_rosbag2_sqlite(
            path, [](const BagTopic&, const BagMessageView&) {}, nullptr);
      },
      {path.string()});
}

TEST(Rosbag2SqliteErrors, FolderOfAnotherStorage) {
  const test::TempDir dir;
  test::write_file(dir / "metadata.yaml",
                   "rosbag2_bagfile_information:\n  storage_identifier: mcap\n");
  test::expect_input_error([&] { rosbag2_sqlite_contents(dir.path()); },
                           {dir.path().string(), "storage_identifier 'mcap'"});
  const test::TempDir empty;
  test::expect_input_error([&] { rosbag2_sqlite_contents(empty.path()); }, {"metadata.yaml"});
  EXPECT_EQ(rosbag2_folder_format(empty.path()), std::nullopt);
}

}  // namespace
}  // namespace floorgrid::io
