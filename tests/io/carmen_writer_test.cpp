#include "floorgrid/io/logs/carmen_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::data_path;
using test::read_file;
using test::run_command;
using test::TempDir;

constexpr double pi = std::numbers::pi;

LaserScan make_scan(const std::string& type, std::size_t beams, double increment, double max_range,
                    double timestamp, std::mt19937& random) {
  // Below the max range, as a real laser's: readings spread beyond it would overrule it (the
  // reader lets them win over a PARAM).
  std::uniform_real_distribution<float> range(0.02f, static_cast<float>(max_range) * 0.999f);
  std::uniform_real_distribution<double> any(-100.0, 100.0);
  LaserScan scan;
  scan.type = type;
  scan.angle_increment = increment;
  scan.max_range = max_range;
  for (std::size_t i = 0; i < beams; ++i)
    scan.ranges.push_back(range(random));
  scan.laser_pose = {any(random), any(random), any(random) / 30.0};
  scan.robot_pose = {any(random), any(random), 0.1 + 0.2};
  scan.timestamp = timestamp;
  return scan;
}

// A log with awkward numbers: digits that need all 17 places, equal timestamps, a no-return,
// a NaN reading, a rear laser and a scan with settings FLASER cannot say.
RobotLog awkward_log() {
  std::mt19937 random(42);
  RobotLog log;
  const double t0 = 1071078718.462310;
  for (int i = 0; i < 20; ++i) {
    OdometryReading odometry;
    odometry.pose = {std::sin(i) * 1e3, 1.0 / 3.0 + i, std::nextafter(pi, 4.0) - i * 0.1};
    odometry.tv = 0.1 * i;
    odometry.rv = -1e-17 * i;
    odometry.accel = 1e300;
    odometry.timestamp = t0 + (i / 2) * 0.1;  // pairs of equal timestamps
    log.odometry.push_back(odometry);
  }
  for (int i = 0; i < 6; ++i) {
    log.scans.push_back(make_scan("FLASER", 360, pi / 360, 80.99, t0 + i * 0.2, random));
  }
  log.scans[1].ranges[5] = 81.91f;
  log.scans[2].ranges[7] = std::numeric_limits<float>::quiet_NaN();
  log.scans.push_back(make_scan("RLASER", 181, pi / 180, 50.0, t0 + 0.3, random));
  log.scans.back().laser_pose.theta = pi;
  LaserScan odd = make_scan("FLASER", 100, 0.0123, 30.0, t0 + 1.5, random);
  odd.start_angle = -2.0;
  log.scans.push_back(odd);
  return log;
}

void expect_same_pose(const Pose2& a, const Pose2& b) {
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.theta, b.theta);
}

void expect_same_ranges(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i])) {
      EXPECT_TRUE(std::isnan(b[i])) << "beam " << i;
    } else {
      EXPECT_EQ(a[i], b[i]) << "beam " << i;
    }
  }
}

// Everything a log says, compared exactly (== on doubles and floats).
void expect_same_log(const RobotLog& written, const RobotLog& read, bool same_types = true) {
  ASSERT_EQ(written.odometry.size(), read.odometry.size());
  for (std::size_t i = 0; i < written.odometry.size(); ++i) {
    const OdometryReading& a = written.odometry[i];
    const OdometryReading& b = read.odometry[i];
    expect_same_pose(a.pose, b.pose);
    EXPECT_EQ(a.tv, b.tv);
    EXPECT_EQ(a.rv, b.rv);
    EXPECT_EQ(a.accel, b.accel);
    EXPECT_EQ(a.timestamp, b.timestamp);
  }
  ASSERT_EQ(written.scans.size(), read.scans.size());
  for (std::size_t i = 0; i < written.scans.size(); ++i) {
    const LaserScan& a = written.scans[i];
    const LaserScan& b = read.scans[i];
    if (same_types) {
      EXPECT_EQ(a.type, b.type) << "scan " << i;
    }
    EXPECT_EQ(a.start_angle, b.start_angle) << "scan " << i;
    EXPECT_EQ(a.angle_increment, b.angle_increment) << "scan " << i;
    EXPECT_EQ(a.max_range, b.max_range) << "scan " << i;
    expect_same_ranges(a.ranges, b.ranges);
    expect_same_pose(a.laser_pose, b.laser_pose);
    expect_same_pose(a.robot_pose, b.robot_pose);
    EXPECT_EQ(a.timestamp, b.timestamp) << "scan " << i;
  }
}

TEST(CarmenWriterTest, RoundTripGivesIdenticalPosesRangesAndTimestamps) {
  TempDir dir;
  const RobotLog log = awkward_log();
  write_carmen(log, dir / "out.log");
  const RobotLog read = read_carmen(dir / "out.log");
  ASSERT_EQ(read.scans.size(), log.scans.size());
  // Scans come back in timestamp order within each type; this log's order is already that
  // within FLASER, but the RLASER sits between them by time: compare per type.
  RobotLog by_type = log;
  std::stable_sort(
      by_type.scans.begin(), by_type.scans.end(),
      [](const LaserScan& a, const LaserScan& b) { return a.timestamp < b.timestamp; });
  RobotLog read_by_time = read;
  std::stable_sort(
      read_by_time.scans.begin(), read_by_time.scans.end(),
      [](const LaserScan& a, const LaserScan& b) { return a.timestamp < b.timestamp; });
  by_type.scans.back().type = "ROBOTLASER1";  // FLASER cannot carry a -2 rad start angle
  expect_same_log(by_type, read_by_time);
  EXPECT_TRUE(std::isnan(read_by_time.scans[3].ranges[7]));  // F0 F1 RLASER F2 ...
  EXPECT_FALSE(read_by_time.scans[1].is_return(5));          // 81.91 >= 80.99
}

TEST(CarmenWriterTest, GzOutputIsAValidGzipFileThatReadsBack) {
  TempDir dir;
  const RobotLog log = awkward_log();
  write_carmen(log, dir / "out.log.gz");
  const std::string bytes = read_file(dir / "out.log.gz");
  ASSERT_GT(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
  EXPECT_EQ(run_command("gzip -t '" + (dir / "out.log.gz").string() + "'").status, 0);
  // The gzip tool decompresses it to exactly the plain text.
  EXPECT_EQ(run_command("zcat '" + (dir / "out.log.gz").string() + "'").out, format_carmen(log));
  write_carmen(log, dir / "out.log");
  const RobotLog plain = read_carmen(dir / "out.log");
  const RobotLog packed = read_carmen(dir / "out.log.gz");
  expect_same_log(plain, packed);
  // Atomic write: nothing but the two outputs is left in the folder.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 2u);
}

TEST(CarmenWriterTest, OutputFollowsCarmensTextFormat) {
  TempDir dir;
  const RobotLog log = awkward_log();
  write_carmen(log, dir / "out.log");
  const std::string file = (dir / "out.log").string();
  const std::string text = read_file(dir / "out.log");
  EXPECT_EQ(text.rfind("# CARMEN Logfile\n", 0), 0u);
  EXPECT_NE(text.find("# message formats defined: PARAM ODOM FLASER"), std::string::npos);
  EXPECT_NE(text.find("\nPARAM laser_front_laser_resolution 0.5 "), std::string::npos);
  EXPECT_NE(text.find("\nPARAM robot_front_laser_max 80.99 "), std::string::npos);
  EXPECT_NE(text.find("\nPARAM laser_rear_laser_resolution 1 "), std::string::npos);
  EXPECT_NE(text.find("\nPARAM robot_rear_laser_max 50 "), std::string::npos);
  // Field counts per type, checked by awk: ODOM 10; FLASER/RLASER n + 11; ROBOTLASER1
  // n + 24 with no remissions; host always in the second-to-last field.
  const auto bad = run_command(
      "awk '$1==\"ODOM\" && NF!=10 {b++} ($1==\"FLASER\"||$1==\"RLASER\") && NF!=$2+11 {b++} "
      "$1==\"ROBOTLASER1\" && NF!=$9+24 {b++} $1!~/^#/ && $(NF-1)!=\"floorgrid\" {b++} "
      "END {print b+0}' '" +
      file + "'");
  EXPECT_EQ(bad.out, "0\n");
  const auto counts = run_command(
      "grep -c -e '^ODOM ' -e '^FLASER ' -e '^RLASER ' "
      "-e '^ROBOTLASER1 ' '" +
      file + "'");
  EXPECT_EQ(std::stoul(counts.out), log.odometry.size() + log.scans.size());
  // Interleaved in timestamp order across types (the timestamp is third from the end).
  const auto order = run_command(
      "awk '$1!~/^#/ && $1!=\"PARAM\" { t=$(NF-2)+0; if (n && t<last) b++; n++; last=t } "
      "END {print b+0, n}' '" +
      file + "'");
  EXPECT_EQ(order.out, "0 " + std::to_string(log.odometry.size() + log.scans.size()) + "\n");
}

TEST(CarmenWriterTest, RoundTripOfTheFr079LogIsExact) {
  FLOORGRID_REQUIRE_DATA("fr079/freiburg-079-corrected.log.gz");
  TempDir dir;
  const CarmenLog original = read_carmen_log(data_path("fr079/freiburg-079-corrected.log.gz"));
  write_carmen(original, dir / "copy.log.gz");
  const CarmenLog copy = read_carmen_log(dir / "copy.log.gz");
  expect_same_log(original, copy);
  EXPECT_EQ(copy.summary.messages.at("ODOM").kept, original.odometry.size());
  EXPECT_EQ(copy.summary.messages.at("ODOM").skipped_zero_timestamp, 0u);
  EXPECT_EQ(copy.summary.laser_configs.at(0).angle_increment.source, SettingSource::param);
  EXPECT_EQ(copy.summary.ranges.no_return, original.summary.ranges.no_return);
}

TEST(CarmenWriterTest, RefusesLogsItCannotWriteFaithfully) {
  TempDir dir;
  RobotLog log = awkward_log();
  log.odometry[3].timestamp = 0.0;
  EXPECT_THROW(format_carmen(log), std::invalid_argument);
  log = awkward_log();
  log.odometry[3].timestamp = log.odometry[2].timestamp - 1.0;
  EXPECT_THROW(format_carmen(log), std::invalid_argument);
  log = awkward_log();
  log.scans[4].timestamp = log.scans[3].timestamp - 0.5;
  EXPECT_THROW(format_carmen(log), std::invalid_argument);
  log = awkward_log();
  log.scans[0].ranges.clear();
  EXPECT_THROW(format_carmen(log), std::invalid_argument);
  log = awkward_log();
  log.scans[0].max_range = std::numeric_limits<double>::infinity();
  EXPECT_THROW(format_carmen(log), std::invalid_argument);
  CarmenWriteOptions options;
  options.host = "two words";
  EXPECT_THROW(format_carmen(awkward_log(), options), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "never.log"));
}

TEST(CarmenWriterTest, UnwritableFolderIsInputErrorNamingTheFile) {
  TempDir dir;
  const auto target = dir / "no" / "such" / "folder" / "out.log";
  try {
    write_carmen(awkward_log(), target);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), target.string());
  }
}

}  // namespace
}  // namespace floorgrid::io
