// A bag read as a run (io/bag_log): the same run as the CARMEN log it was written from, odometry
// from /tf alone, a laser mounted off-centre and upside down, and the choices and refusals of
// topics. The bags are written by an independent writer (tests/bags/write_ros1_bag.py, Debian's
// python3-rosbag) from fr079's first 200 scans.
#include "floorgrid/io/logs/bag_log.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "floorgrid/io/dataset/robot_log_reader.hpp"
#include "floorgrid/io/files/line_reader.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "tests/io/ros1_bag_test_support.hpp"
#include "tests/support/bag_writers.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid::io {
namespace {

namespace fs = std::filesystem;
using ros1_test::bags;
using test::TempDir;

/// fr079's CARMEN log read by the CARMEN reader: the run the bags were written from.
const CarmenLog& carmen_run() {
  static const CarmenLog log =
      read_carmen_log(test::data_path("fr079/freiburg-079-corrected.log.gz"));
  return log;
}

void expect_same_pose(const Pose2& a, const Pose2& b, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, 1e-9) << what;
  EXPECT_NEAR(a.y, b.y, 1e-9) << what;
  EXPECT_NEAR(normalize_angle(a.theta - b.theta), 0.0, 1e-9) << what;
}

/// Expects `log` to hold the first `n` scans of fr079's CARMEN log: the same readings, laser
/// settings, poses and times.
void expect_same_run(const ReadRobotLog& log, std::size_t n, const std::string& name) {
  const CarmenLog& carmen = carmen_run();
  ASSERT_EQ(log.scans.size(), n) << name;
  {
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      const LaserScan& a = log.scans[i];
      const LaserScan& b = carmen.scans[i];
      const std::string what = name + " scan " + std::to_string(i);
      EXPECT_NEAR(a.timestamp, b.timestamp, 1e-6) << what;
      EXPECT_EQ(a.ranges, b.ranges) << what;  // float32 in both: bit for bit
      // LaserScan's angles and ranges are float32; read as the decimal degrees and metres they
      // round from, they are CARMEN's doubles exactly.
      EXPECT_EQ(a.start_angle, b.start_angle) << what;
      EXPECT_EQ(a.angle_increment, b.angle_increment) << what;
      EXPECT_EQ(a.max_range, b.max_range) << what;
      EXPECT_EQ(a.min_range, b.min_range) << what;
      expect_same_pose(a.robot_pose, b.robot_pose, what);
      expect_same_pose(a.laser_pose, b.laser_pose, what);
      for (std::size_t k = 0; k < a.ranges.size(); k += 37)
        EXPECT_EQ(a.range_kind(k), b.range_kind(k)) << what << " beam " << k;
    }
  }
  EXPECT_EQ(log.odometry.size(), n) << name;
  EXPECT_TRUE(log.summary.warnings.empty()) << name;
}

TEST(BagLog, TheSameRunAsTheCarmenLogItWasWrittenFrom) {
  REQUIRE_ROS1_BAGS();
  for (const char* compression : {"none", "lz4"}) {
    const fs::path bag =
        bags().bag(std::string("run-") + compression, std::string("--compression ") + compression);
    expect_same_run(read_robot_log(bag), 200, std::string("ROS 1 ") + compression);
  }
}

TEST(BagLog, TheSameRunFromMcapAndRosbag2) {
  FLOORGRID_REQUIRE_BAG_RECORDS(records);
  const fs::path bags_dir = fs::path(FLOORGRID_SOURCE_DIR) / "tests/bags";
  TempDir dir;
  std::map<std::string, std::string> writers = {
      {"db3", "/usr/bin/python3 " + test::quoted(bags_dir / "write_rosbag2_db3.py")}};
  if (test::mcap_writer_missing().empty())
    writers["mcap"] = "node " + test::quoted(bags_dir / "write_mcap.mjs");
  for (const auto& [name, writer] : writers) {
    const fs::path out = dir / ("run." + name);
    const test::CommandResult made =
        test::run_command(writer + " " + test::quoted(records) + " " + test::quoted(out) +
                          (name == "mcap" ? " --compression zstd" : ""));
    ASSERT_EQ(made.status, 0) << made.err;
    const ReadRobotLog log = read_robot_log(out);
    expect_same_run(log, 120, name);  // bag_records: the first 120 scans
  }
  if (!test::mcap_writer_missing().empty())
    GTEST_SKIP() << "rosbag2 sqlite3 checked; MCAP not: " << test::mcap_writer_missing();
}

TEST(BagLog, OdometryFromTfWhenThereIsNoOdometryTopic) {
  REQUIRE_ROS1_BAGS();
  const BagLog with = read_bag_log(bags().bag("run-lz4", "--compression lz4"));
  const BagLog without = read_bag_log(bags().bag("no-odom", "--no-odom"));
  EXPECT_EQ(with.odometry_source, "/odom");
  EXPECT_EQ(without.odometry_source, "/tf (odom -> base_link)");
  ASSERT_EQ(with.scans.size(), without.scans.size());
  for (std::size_t i = 0; i < with.scans.size(); ++i)
    expect_same_pose(with.scans[i].robot_pose, without.scans[i].robot_pose, std::to_string(i));
}

TEST(BagLog, ScansInLongOdometryGapsAreReported) {
  REQUIRE_ROS1_BAGS();
  // fr079 scans at about 4.5 Hz: odometry at every 20th scan leaves gaps of about 4 s.
  const BagLog sparse = read_bag_log(bags().bag("sparse-odom", "--odom-every 20"));
  ASSERT_EQ(sparse.scans.size(), 200u);
  ASSERT_EQ(sparse.summary.warnings.size(), 1u);
  EXPECT_NE(sparse.summary.warnings[0].find("odometry gaps longer than 2 s"), std::string::npos)
      << sparse.summary.warnings[0];
  EXPECT_TRUE(read_bag_log(bags().bag("run-lz4", "--compression lz4")).summary.warnings.empty());
}

TEST(BagLog, ALaserMountedOffCentreRotatedAndUpsideDown) {
  REQUIRE_ROS1_BAGS();
  const Pose2 mount{0.2, 0.1, 0.5};
  const BagLog upright = read_bag_log(bags().bag("mounted", "--mount 0.2,0.1,0.5"));
  const BagLog flipped =
      read_bag_log(bags().bag("flipped", "--mount 0.2,0.1,0.5,3.141592653589793"));
  const CarmenLog& carmen = carmen_run();
  EXPECT_FALSE(upright.laser_upside_down);
  EXPECT_TRUE(flipped.laser_upside_down);
  ASSERT_EQ(flipped.scans.size(), 200u);
  for (std::size_t i = 0; i < flipped.scans.size(); i += 7) {
    const LaserScan& original = carmen.scans[i];
    for (const BagLog* log : {&upright, &flipped}) {
      const LaserScan& s = log->scans[i];
      // The robot's pose is the odometry's; the laser sits at the mount on it.
      expect_same_pose(s.robot_pose, original.robot_pose, "robot " + std::to_string(i));
      expect_same_pose(s.laser_pose, original.robot_pose.compose(mount),
                       "laser " + std::to_string(i));
    }
    // Upright, beam k looks at a_k in the laser's frame; upside down, the same reading looks at
    // -a_k: its beams turn clockwise, read in reverse.
    const std::size_t n = original.ranges.size();
    for (std::size_t k = 0; k < n; k += 11) {
      const LaserScan& up = upright.scans[i];
      const LaserScan& down = flipped.scans[i];
      EXPECT_EQ(up.ranges[k], original.ranges[k]);
      EXPECT_NEAR(up.angle(k), original.angle(k), 1e-6);
      EXPECT_EQ(down.ranges[n - 1 - k], original.ranges[k]);
      EXPECT_NEAR(down.angle(n - 1 - k), -original.angle(k), 1e-6);
    }
  }
}

TEST(BagLog, ScanTopicsFoundChosenOrRefused) {
  REQUIRE_ROS1_BAGS();
  const fs::path two = bags().bag("two-scans", "--extra-scan-topic /scan_rear");
  test::expect_input_error([&] { read_bag_log(two); },
                           {two.string(), "/scan, /scan_rear", "log_topics.scan"});
  BagLogOptions options;
  options.scan_topic = "/scan_rear";
  EXPECT_EQ(read_bag_log(two, options).scans.size(), 200u);
  options.scan_topic = "/odom";
  test::expect_input_error([&] { read_bag_log(two, options); },
                           {"/odom is a nav_msgs/Odometry, not a sensor_msgs/LaserScan"});
  options.scan_topic = "/front";
  test::expect_input_error([&] { read_bag_log(two, options); }, {"no topic /front", "/scan_rear"});
  const fs::path none = bags().bag("no-scans", "--no-scan");
  test::expect_input_error([&] { read_bag_log(none); },
                           {none.string(), "no sensor_msgs/LaserScan topic", "/odom"});
}

TEST(BagLog, InfoAndPairsOnBags) {
  REQUIRE_ROS1_BAGS();
  const fs::path bag = bags().bag("run-lz4", "--compression lz4");
  const test::CommandResult info = test::run_floorgrid("info --json " + test::quoted(bag));
  ASSERT_EQ(info.status, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["format"], "ROS 1 bag");
  EXPECT_EQ(j["scan_topic"], "/scan");
  EXPECT_EQ(j["laser_scans"], 200);
  std::map<std::string, std::uint64_t> counts;
  for (const auto& t : j["topics"])
    counts[t["topic"]] = t["messages"];
  const std::map<std::string, std::uint64_t> written = {
      {"/scan", 200}, {"/odom", 200}, {"/tf", 200}, {"/tf_static", 1}};
  EXPECT_EQ(counts, written);

  // A truncated bag: exit 2 with the byte offset.
  TempDir dir;
  const std::string whole = test::read_file(bags().bag("run-none", "--compression none"));
  test::write_file(dir / "cut.bag", whole.substr(0, whole.size() / 2));
  const test::CommandResult cut = test::run_floorgrid("info " + test::quoted(dir / "cut.bag"));
  EXPECT_EQ(cut.status, 2) << cut.out << cut.err;
  EXPECT_NE(cut.err.find("at byte"), std::string::npos) << cut.err;
}

/// `pairs` on a dataset of fr079's maps and `log`: its result.
test::CommandResult pairs_on(const fs::path& log, const TempDir& dir,
                             const std::string& more = "") {
  const fs::path data = test::data_path("fr079");
  test::write_file(
      dir / "dataset.yaml",
      "floorplan: " + (data / "floorplan.png").string() +
          "\nfloorplan_resolution: 0.05\ngridmap: " + (data / "slam_map.png").string() +
          "\ngridmap_resolution: 0.05\nodometry_noise: [0.05, 0.01, 0.02, 0.05]\nlog: " +
          log.string() + "\n" + more);
  return test::run_floorgrid("pairs " + test::quoted(dir.path()) + " --out " +
                             test::quoted(dir / "pairs.csv"));
}

TEST(BagLog, PairsFromABagAreTheCarmenLogsPairs) {
  REQUIRE_ROS1_BAGS();
  // The CARMEN log up to its 200th scan: the run the bags hold.
  TempDir carmen_dir, bag_dir;
  {
    LineReader in(test::data_path("fr079/freiburg-079-corrected.log.gz"));
    std::string text;
    std::string_view line;
    for (int scans = 0; scans < 200 && in.next(line);) {
      text.append(line) += '\n';
      scans += line.starts_with("FLASER ") ? 1 : 0;
    }
    test::write_file(carmen_dir / "run.log", text);
  }
  // The plan's scale given: 200 scans are too few to estimate it.
  const std::string scale = "floorplan_scale: 1.11\n";
  const test::CommandResult from_carmen = pairs_on(carmen_dir / "run.log", carmen_dir, scale);
  const test::CommandResult from_bag =
      pairs_on(bags().bag("run-lz4", "--compression lz4"), bag_dir, scale);
  ASSERT_EQ(from_carmen.status, 0) << from_carmen.err;
  ASSERT_EQ(from_bag.status, 0) << from_bag.err;
  const ReferencePairs a = read_pairs_csv(carmen_dir / "pairs.csv");
  const ReferencePairs b = read_pairs_csv(bag_dir / "pairs.csv");
  ASSERT_GT(a.size(), 1000);
  ASSERT_EQ(a.size(), b.size());
  // The same pairs but for the last bit of the headings (yaw -> quaternion -> yaw).
  EXPECT_LT((a.points_in_plan - b.points_in_plan).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.points_in_grid - b.points_in_grid).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(BagLog, BadBagsStopTheJobWithExit2) {
  REQUIRE_ROS1_BAGS();
  {  // no scans
    TempDir dir;
    const test::CommandResult pairs = pairs_on(bags().bag("no-scans", "--no-scan"), dir);
    EXPECT_EQ(pairs.status, 2) << pairs.out << pairs.err;
    EXPECT_NE(pairs.err.find("no sensor_msgs/LaserScan topic"), std::string::npos) << pairs.err;
    EXPECT_FALSE(fs::exists(dir / "pairs.csv"));
  }
  {  // a LaserScan whose ranges array says 100000 readings where 360 follow
    TempDir dir;
    std::string bytes = test::read_file(bags().bag("run-none", "--compression none"));
    const float range_max = 80.99f;
    const std::uint32_t beams = 360, lie = 100000;
    std::string pattern(8, '\0');
    std::memcpy(pattern.data(), &range_max, 4);
    std::memcpy(pattern.data() + 4, &beams, 4);
    const std::size_t at = bytes.find(pattern);
    ASSERT_NE(at, std::string::npos);
    std::memcpy(bytes.data() + at + 4, &lie, 4);
    test::write_file(dir / "lying.bag", bytes);
    const test::CommandResult pairs = pairs_on(dir / "lying.bag", dir);
    EXPECT_EQ(pairs.status, 2) << pairs.out << pairs.err;
    EXPECT_NE(pairs.err.find("topic /scan: ranges says 100000 elements"), std::string::npos)
        << pairs.err;
    EXPECT_FALSE(fs::exists(dir / "pairs.csv"));
  }
}

}  // namespace
}  // namespace floorgrid::io
