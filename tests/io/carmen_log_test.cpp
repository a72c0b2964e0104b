#include "floorgrid/io/logs/carmen_log.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::data_path;
using test::read_file;
using test::run_command;
using test::TempDir;
using test::write_file;

constexpr double pi = std::numbers::pi;

// A FLASER line with the given ranges (as text), poses and timestamp.
std::string flaser(const std::vector<std::string>& ranges, const std::string& poses,
                   const std::string& timestamp, const std::string& type = "FLASER") {
  std::string line = type + " " + std::to_string(ranges.size());
  for (const auto& range : ranges)
    line += " " + range;
  return line + " " + poses + " " + timestamp + " testhost " + timestamp + "\n";
}

std::string flaser_of(std::size_t beams, const std::string& timestamp) {
  return flaser(std::vector<std::string>(beams, "1.5"), "0 0 0 0 0 0", timestamp);
}

std::string odom(const std::string& pose, const std::string& timestamp) {
  return "ODOM " + pose + " 0 0 0 " + timestamp + " testhost " + timestamp + "\n";
}

CarmenLog read_text(const TempDir& dir, const std::string& text,
                    const CarmenReadOptions& options = {}) {
  write_file(dir / "test.log", text);
  return read_carmen_log(dir / "test.log", options);
}

TEST(CarmenLogTest, ReadsOdometryFields) {
  TempDir dir;
  const CarmenLog log =
      read_text(dir, "ODOM 1.25 -2.5 0.75 0.3 -0.1 0.05 100.5 merci 100.6\n" + flaser_of(3, "101"));
  ASSERT_EQ(log.odometry.size(), 1u);
  const OdometryReading& odometry = log.odometry[0];
  EXPECT_EQ(odometry.pose.x, 1.25);
  EXPECT_EQ(odometry.pose.y, -2.5);
  EXPECT_EQ(odometry.pose.theta, 0.75);
  EXPECT_EQ(odometry.tv, 0.3);
  EXPECT_EQ(odometry.rv, -0.1);
  EXPECT_EQ(odometry.accel, 0.05);
  EXPECT_EQ(odometry.timestamp, 100.5);
  EXPECT_EQ(odometry.line, 1u);
}

TEST(CarmenLogTest, ReadsFlaserWithParamSettings) {
  TempDir dir;
  const CarmenLog log =
      read_text(dir,
                "# a comment\n"
                "PARAM laser_front_laser_resolution 1.0 0 h 0\n"
                "PARAM robot_front_laser_max 10 0 h 0\n" +
                    flaser({"1.5", "2.25", "10", "11"}, "0.1 0.2 0.3 1.1 1.2 1.3", "7.5"));
  ASSERT_EQ(log.scans.size(), 1u);
  const LaserScan& scan = log.scans[0];
  EXPECT_EQ(scan.type, "FLASER");
  EXPECT_EQ(scan.line, 4u);
  ASSERT_EQ(scan.ranges.size(), 4u);
  EXPECT_EQ(scan.ranges[0], 1.5f);
  EXPECT_EQ(scan.ranges[1], 2.25f);
  EXPECT_EQ(scan.ranges[3], 11.0f);
  EXPECT_DOUBLE_EQ(scan.start_angle, -pi / 2);
  EXPECT_DOUBLE_EQ(scan.angle_increment, pi / 180);
  EXPECT_DOUBLE_EQ(scan.angle(2), -pi / 2 + 2 * pi / 180);
  EXPECT_EQ(scan.max_range, 10.0);
  EXPECT_EQ(scan.laser_pose.x, 0.1);
  EXPECT_EQ(scan.laser_pose.y, 0.2);
  EXPECT_EQ(scan.laser_pose.theta, 0.3);
  EXPECT_EQ(scan.robot_pose.x, 1.1);
  EXPECT_EQ(scan.robot_pose.y, 1.2);
  EXPECT_EQ(scan.robot_pose.theta, 1.3);
  EXPECT_EQ(scan.timestamp, 7.5);
  EXPECT_TRUE(scan.is_return(0));
  EXPECT_TRUE(scan.is_return(1));
  EXPECT_FALSE(scan.is_return(2));  // at max range
  EXPECT_FALSE(scan.is_return(3));  // beyond max range

  ASSERT_EQ(log.summary.laser_configs.size(), 1u);
  const LaserConfigUsage& config = log.summary.laser_configs[0];
  EXPECT_EQ(config.angle_increment.source, SettingSource::param);
  EXPECT_EQ(config.angle_increment.detail, "laser_front_laser_resolution");
  EXPECT_EQ(config.max_range.source, SettingSource::param);
  EXPECT_EQ(config.max_range.detail, "robot_front_laser_max");
  EXPECT_EQ(config.min_range.source, SettingSource::guess);
  EXPECT_EQ(config.scans, 1u);
  EXPECT_EQ(log.summary.params.at("robot_front_laser_max"), "10");
  EXPECT_EQ(log.summary.ranges.no_return, 2u);
  EXPECT_EQ(log.summary.ranges.hits, 2u);
}

TEST(CarmenLogTest, LaserMaxrangeParamBeatsRobotFrontLaserMax) {
  TempDir dir;
  const CarmenLog log = read_text(dir,
                                  "PARAM laser_front_laser_maxrange 30 0 h 0\n"
                                  "PARAM robot_front_laser_max 10 0 h 0\n" +
                                      flaser_of(3, "1"));
  EXPECT_EQ(log.scans[0].max_range, 30.0);
  EXPECT_EQ(log.summary.laser_configs[0].max_range.detail, "laser_front_laser_maxrange");
}

TEST(CarmenLogTest, GuessesIncrementFromBeamCountAsCarmenDoes) {
  TempDir dir;
  const std::vector<std::size_t> beams = {180, 181, 360, 361, 400, 401, 5};
  const std::vector<double> expected = {pi / 180, pi / 180, pi / 360, pi / 360,
                                        pi / 720, pi / 720, pi / 4};
  std::string text;
  for (std::size_t i = 0; i < beams.size(); ++i)
    text += flaser_of(beams[i], std::to_string(i + 1));
  const CarmenLog log = read_text(dir, text);
  ASSERT_EQ(log.scans.size(), beams.size());
  for (std::size_t i = 0; i < beams.size(); ++i) {
    EXPECT_EQ(log.scans[i].ranges.size(), beams[i]);
    EXPECT_DOUBLE_EQ(log.scans[i].angle_increment, expected[i]) << beams[i] << " beams";
    EXPECT_EQ(log.scans[i].max_range, 80.0);
    EXPECT_DOUBLE_EQ(log.scans[i].start_angle, -pi / 2);
  }
  ASSERT_EQ(log.summary.laser_configs.size(), beams.size());
  for (const LaserConfigUsage& config : log.summary.laser_configs) {
    EXPECT_EQ(config.angle_increment.source, SettingSource::guess);
    EXPECT_EQ(config.max_range.source, SettingSource::guess);
  }
  EXPECT_EQ(log.summary.beams_per_scan.size(), beams.size());
  EXPECT_EQ(log.summary.beams_per_scan.at(360), 1u);
}

TEST(CarmenLogTest, ManifestOverridesParamsMessagesAndGuesses) {
  TempDir dir;
  CarmenReadOptions options;
  options.laser.max_range = 5.0;
  options.laser.min_range = 0.1;
  options.laser.start_angle = -1.0;
  options.laser.angle_increment = 0.01;
  const CarmenLog log = read_text(dir,
                                  "PARAM laser_front_laser_resolution 1.0 0 h 0\n"
                                  "PARAM robot_front_laser_max 10 0 h 0\n" +
                                      flaser_of(3, "1") +
                                      "ROBOTLASER1 0 -2.0 3.0 0.015 30.0 0.01 0 2 1.0 2.0 0 "
                                      "0 0 0 0 0 0 0 0 0 0 0 2 h 2\n",
                                  options);
  ASSERT_EQ(log.scans.size(), 2u);
  for (const LaserScan& scan : log.scans) {
    EXPECT_EQ(scan.max_range, 5.0);
    EXPECT_EQ(scan.min_range, 0.1);
    EXPECT_EQ(scan.start_angle, -1.0);
    EXPECT_EQ(scan.angle_increment, 0.01);
  }
  for (const LaserConfigUsage& config : log.summary.laser_configs) {
    EXPECT_EQ(config.max_range.source, SettingSource::manifest);
    EXPECT_EQ(config.min_range.source, SettingSource::manifest);
    EXPECT_EQ(config.start_angle.source, SettingSource::manifest);
    EXPECT_EQ(config.angle_increment.source, SettingSource::manifest);
    EXPECT_EQ(config.max_range.detail, "laser.max_range");
  }
}

TEST(CarmenLogTest, RearLaserUsesRearParamsAndKeepsItsBackwardPose) {
  TempDir dir;
  const CarmenLog log = read_text(
      dir,
      "PARAM laser_front_laser_resolution 1.0 0 h 0\n"
      "PARAM laser_rear_laser_resolution 0.25 0 h 0\n"
      "PARAM robot_rear_laser_max 20 0 h 0\n" +
          flaser(std::vector<std::string>(8, "2"), "1 2 3.2415926 1 2 0.1", "4.0", "RLASER"));
  ASSERT_EQ(log.scans.size(), 1u);
  const LaserScan& scan = log.scans[0];
  EXPECT_EQ(scan.type, "RLASER");
  EXPECT_DOUBLE_EQ(scan.angle_increment, pi / 720);
  EXPECT_EQ(scan.max_range, 20.0);
  EXPECT_DOUBLE_EQ(scan.start_angle, -pi / 2);  // relative to the laser pose, as CARMEN
  EXPECT_EQ(scan.laser_pose.theta, 3.2415926);  // which already faces backwards
  EXPECT_EQ(log.summary.laser_configs[0].angle_increment.detail, "laser_rear_laser_resolution");
}

TEST(CarmenLogTest, RobotLaser1UsesItsOwnSettings) {
  TempDir dir;
  // laser_type start fov resolution maxrange accuracy remission_mode n r1 r2 r3 m rem1 rem2
  // laser pose, robot pose, tv rv forward side turn_axis, timestamp host logger_timestamp
  const CarmenLog log = read_text(dir,
                                  "PARAM laser_front_laser_resolution 1.0 0 h 0\n"
                                  "ROBOTLASER1 0 -2.0 3.0 0.015 30.0 0.01 1 3 1.0 30.0 2.5 2 "
                                  "7 8 0.1 0.2 0.3 1.0 2.0 0.25 0.5 0.6 0.7 0.8 0.9 12.5 h 12.6\n");
  ASSERT_EQ(log.scans.size(), 1u);
  const LaserScan& scan = log.scans[0];
  EXPECT_EQ(scan.type, "ROBOTLASER1");
  EXPECT_EQ(scan.start_angle, -2.0);
  EXPECT_EQ(scan.angle_increment, 0.015);
  EXPECT_EQ(scan.max_range, 30.0);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_EQ(scan.ranges[2], 2.5f);
  EXPECT_FALSE(scan.is_return(1));  // 30 = maximum_range
  EXPECT_EQ(scan.laser_pose.x, 0.1);
  EXPECT_EQ(scan.laser_pose.theta, 0.3);
  EXPECT_EQ(scan.robot_pose.x, 1.0);
  EXPECT_EQ(scan.robot_pose.theta, 0.25);
  EXPECT_EQ(scan.timestamp, 12.5);
  EXPECT_EQ(log.summary.laser_configs[0].angle_increment.source, SettingSource::message);
}

TEST(CarmenLogTest, SkipsAndCountsOtherLinesByType) {
  TempDir dir;
  const CarmenLog log = read_text(dir,
                                  "# message formats defined: PARAM ODOM FLASER\n"
                                  "#another\n"
                                  "\n"
                                  "   \t \n"
                                  "PARAM robot_use_laser on nohost 0\n"
                                  "NEFF 10\n"
                                  "NEFF 27.6 0 pippo 0\n"
                                  "SYNC tag\n"
                                  "TRUEPOS 1 2 3 4 5 6 1.0 h 1.0\n"
                                  "RAWLASER1 0 -1.5 3.1 0.01 50 0.01 0 1 2.0 0 1.0 h 1.0\n" +
                                      odom("0 0 0", "1") + flaser_of(2, "1"));
  const auto& messages = log.summary.messages;
  EXPECT_EQ(log.summary.lines, 12u);
  EXPECT_EQ(messages.at("#").lines, 2u);
  EXPECT_EQ(messages.at("(empty)").lines, 2u);
  EXPECT_EQ(messages.at("PARAM").lines, 1u);
  EXPECT_EQ(messages.at("PARAM").not_data, 1u);
  EXPECT_EQ(messages.at("NEFF").lines, 2u);
  EXPECT_EQ(messages.at("NEFF").not_data, 2u);
  EXPECT_EQ(messages.at("SYNC").lines, 1u);
  EXPECT_EQ(messages.at("TRUEPOS").lines, 1u);
  EXPECT_EQ(messages.at("RAWLASER1").lines, 1u);
  EXPECT_EQ(messages.at("ODOM").kept, 1u);
  EXPECT_EQ(messages.at("FLASER").kept, 1u);
  EXPECT_EQ(log.summary.params.at("robot_use_laser"), "on");
}

TEST(CarmenLogTest, SkipsZeroAndBackwardsTimestampsPerTypeAndKeepsEqualOnes) {
  TempDir dir;
  const CarmenLog log =
      read_text(dir, odom("1 0 0", "1") + odom("2 0 0", "0") + odom("3 0 0", "2") +
                         flaser_of(2, "1.0") + odom("4 0 0", "1.5") + odom("5 0 0", "2") +
                         flaser_of(2, "0.5") + odom("6 0 0", "-3") + flaser_of(2, "1.0") +
                         odom("7 0 0", "3") + odom("8 0 0", "nan"));
  std::vector<double> xs;
  for (const auto& odometry : log.odometry)
    xs.push_back(odometry.pose.x);
  EXPECT_EQ(xs, (std::vector<double>{1, 3, 5, 7}));
  const MessageTypeCount& odometry = log.summary.messages.at("ODOM");
  EXPECT_EQ(odometry.lines, 8u);
  EXPECT_EQ(odometry.kept, 4u);
  EXPECT_EQ(odometry.skipped_zero_timestamp, 3u);  // 0, -3, nan
  EXPECT_EQ(odometry.skipped_backwards_timestamp, 1u);
  const MessageTypeCount& scans = log.summary.messages.at("FLASER");
  EXPECT_EQ(scans.kept, 2u);
  EXPECT_EQ(scans.skipped_backwards_timestamp, 1u);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.scans[0].timestamp, log.scans[1].timestamp);
  EXPECT_EQ(log.summary.first_timestamp, 1.0);
  EXPECT_EQ(log.summary.last_timestamp, 3.0);
  EXPECT_EQ(log.summary.duration, 2.0);
}

TEST(CarmenLogTest, ClassifiesEveryRangeReading) {
  TempDir dir;
  CarmenReadOptions options;
  options.laser.min_range = 0.05;
  const CarmenLog log = read_text(
      dir,
      "PARAM robot_front_laser_max 10 0 h 0\n" +
          flaser({"1", "10", "12", "nan", "-1", "0", "0.01", "inf", "9.99"}, "0 0 0 0 0 0", "1"),
      options);
  const LaserScan& scan = log.scans[0];
  const std::vector<RangeKind> expected = {
      RangeKind::hit,       RangeKind::no_return, RangeKind::no_return,
      RangeKind::invalid,   RangeKind::invalid,   RangeKind::too_close,
      RangeKind::too_close, RangeKind::no_return, RangeKind::hit};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(scan.range_kind(i), expected[i]) << "beam " << i;
  }
  const RangeCounts& counts = log.summary.ranges;
  EXPECT_EQ(counts.total, 9u);
  EXPECT_EQ(counts.hits, 2u);
  EXPECT_EQ(counts.no_return, 3u);
  EXPECT_EQ(counts.too_close, 2u);
  EXPECT_EQ(counts.invalid, 2u);
}

TEST(CarmenLogTest, ReadingPrintedAsTheMaxRangeIsNoReturn) {
  TempDir dir;
  // float(80.99) < 80.99 as doubles: readings are compared at their own precision.
  const CarmenLog log = read_text(dir, "PARAM robot_front_laser_max 80.99 0 h 0\n" +
                                           flaser({"80.99", "80.98"}, "0 0 0 0 0 0", "1"));
  EXPECT_EQ(log.scans[0].range_kind(0), RangeKind::no_return);
  EXPECT_EQ(log.scans[0].range_kind(1), RangeKind::hit);
}

TEST(CarmenLogTest, ToleratesCrLfTabsAndPlusSigns) {
  TempDir dir;
  const CarmenLog log = read_text(dir,
                                  "ODOM\t+1.5  2 3 0 0 0\t5.25 h 5.25\r\n"
                                  "FLASER 2 +1 2e0 0 0 0 0 0 0 5.5 h 5.5\r\n");
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.odometry[0].pose.x, 1.5);
  EXPECT_EQ(log.odometry[0].timestamp, 5.25);
  EXPECT_EQ(log.scans[0].ranges[1], 2.0f);
}

TEST(CarmenLogTest, GzipLogReadsLikeThePlainOne) {
  TempDir dir;
  std::string text = "PARAM laser_front_laser_resolution 0.5 0 h 0\n";
  for (int i = 1; i <= 300; ++i) {
    text += odom(std::to_string(i * 0.1) + " 0 0", std::to_string(i));
    text += flaser_of(361, std::to_string(i) + ".5");
  }
  write_file(dir / "run.log", text);
  ASSERT_EQ(run_command("gzip -kf '" + (dir / "run.log").string() + "'").status, 0);
  const CarmenLog plain = read_carmen_log(dir / "run.log");
  const CarmenLog packed = read_carmen_log(dir / "run.log.gz");
  ASSERT_EQ(packed.scans.size(), 300u);
  ASSERT_EQ(packed.odometry.size(), 300u);
  for (std::size_t i = 0; i < 300; ++i) {
    EXPECT_EQ(packed.scans[i].ranges, plain.scans[i].ranges);
    EXPECT_EQ(packed.scans[i].timestamp, plain.scans[i].timestamp);
    EXPECT_EQ(packed.odometry[i].pose.x, plain.odometry[i].pose.x);
  }
  EXPECT_DOUBLE_EQ(packed.scans[0].angle_increment, pi / 360);
}

// ---- bad input: every error names the file, the 1-based line and the field ----

InputError catch_input_error(const std::function<void()>& run) {
  try {
    run();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError thrown";
  return InputError("none");
}

void expect_located(const InputError& error, const std::filesystem::path& file, long line,
                    const std::string& field) {
  const std::string what = error.what();
  EXPECT_EQ(error.file(), file.string()) << what;
  EXPECT_EQ(error.line(), line) << what;
  EXPECT_EQ(error.field(), field) << what;
  EXPECT_NE(what.find(file.string() + ":" + std::to_string(line) + ":"), std::string::npos) << what;
}

InputError read_bad(const TempDir& dir, const std::string& text) {
  write_file(dir / "bad.log", text);
  return catch_input_error([&] { read_carmen_log(dir / "bad.log"); });
}

TEST(CarmenLogErrorTest, MissingFileNamesIt) {
  TempDir dir;
  const InputError error = catch_input_error([&] { read_carmen_log(dir / "missing.log.gz"); });
  EXPECT_EQ(error.file(), (dir / "missing.log.gz").string());
  EXPECT_NE(std::string(error.what()).find("no such file"), std::string::npos);
}

TEST(CarmenLogErrorTest, TruncatedLineNamesTheFirstMissingRange) {
  TempDir dir;
  const InputError error =
      read_bad(dir, odom("0 0 0", "1") + flaser_of(3, "1") + "FLASER 5 1.0 2.0 3.0\n");
  expect_located(error, dir / "bad.log", 3, "range 4");
  EXPECT_NE(std::string(error.what()).find("ends early"), std::string::npos);
}

TEST(CarmenLogErrorTest, TruncatedLineNamesTheFirstMissingPoseField) {
  TempDir dir;
  expect_located(read_bad(dir, "FLASER 2 1.0 2.0 0.1 0.2\n"), dir / "bad.log", 1, "laser_theta");
}

TEST(CarmenLogErrorTest, NonNumericRangeNamesIt) {
  TempDir dir;
  const InputError error = read_bad(dir, flaser({"1.0", "abc", "3.0"}, "0 0 0 0 0 0", "1"));
  expect_located(error, dir / "bad.log", 1, "range 2");
  EXPECT_NE(std::string(error.what()).find("'abc'"), std::string::npos);
}

TEST(CarmenLogErrorTest, NanOrHugePosesAreRefusedNamingTheField) {
  // NaN in a pose was accepted silently and poisoned every filter.
  TempDir dir;
  expect_located(read_bad(dir, flaser_of(2, "1") + odom("nan 0 0", "2")), dir / "bad.log", 2, "x");
  expect_located(read_bad(dir, flaser({"1", "2"}, "0 0 0 0 0 inf", "1")), dir / "bad.log", 1,
                 "robot_theta");
  expect_located(read_bad(dir, flaser({"1", "2"}, "0 1e300 0 0 0 0", "1")), dir / "bad.log", 1,
                 "laser_y");
}

TEST(CarmenLogErrorTest, ACountOneTooLargeSaysSo) {
  // "FLASER 3" with two readings: the host name lands where the timestamp should be, which said
  // "'timestamp': not a number: 'testhost'".
  TempDir dir;
  const InputError error = read_bad(dir, "FLASER 3 1.0 2.0 0 0 0 0 0 0 5 testhost 5\n");
  expect_located(error, dir / "bad.log", 1, "timestamp");
  EXPECT_NE(std::string(error.what()).find("fewer readings than its count says"), std::string::npos)
      << error.what();
}

TEST(CarmenLogErrorTest, NonNumericTimestampNamesIt) {
  TempDir dir;
  expect_located(read_bad(dir, flaser_of(2, "1") + "ODOM 1 2 3 0 0 0 12:30 h 5\n"), dir / "bad.log",
                 2, "timestamp");
  expect_located(read_bad(dir, "ODOM 1 2 3 0 0 0 1.5x h 5\n"), dir / "bad.log", 1, "timestamp");
}

TEST(CarmenLogErrorTest, AbsurdBeamCountNamesIt) {
  TempDir dir;
  expect_located(read_bad(dir, flaser_of(2, "1") + "FLASER -4 1 2 3 4\n"), dir / "bad.log", 2,
                 "beam count");
  expect_located(read_bad(dir, "FLASER 100001 1 2 3\n"), dir / "bad.log", 1, "beam count");
  expect_located(read_bad(dir, "FLASER 0 0 0 0 0 0 0 1 h 1\n"), dir / "bad.log", 1, "beam count");
  expect_located(read_bad(dir, "FLASER 2.5 1 2 0 0 0 0 0 0 1 h 1\n"), dir / "bad.log", 1,
                 "beam count");
}

TEST(CarmenLogErrorTest, MissingHostOrLoggerTimestampIsAnError) {
  TempDir dir;
  // CARMEN's readers need the host after the timestamp: no "old style" without it.
  expect_located(read_bad(dir, flaser_of(2, "1") + "ODOM 1 2 3 0 0 0 5.0\n"), dir / "bad.log", 2,
                 "host");
  expect_located(read_bad(dir, "FLASER 1 2.0 0 0 0 0 0 0 5.0 h\n"), dir / "bad.log", 1,
                 "logger_timestamp");
}

TEST(CarmenLogErrorTest, ExtraFieldsMeanAWrongCount) {
  TempDir dir;
  expect_located(read_bad(dir, "FLASER 2 1 2 0 0 0 0 0 0 5 h 5 7\n"), dir / "bad.log", 1,
                 "end of line");
  // Three ranges where the count says two: every later field shifts by one.
  expect_located(read_bad(dir, "FLASER 2 1 2 3 0 0 0 0 0 0 5 h 5\n"), dir / "bad.log", 1,
                 "logger_timestamp");
}

TEST(CarmenLogErrorTest, TruncatedGzipLogNamesTheLineReached) {
  TempDir dir;
  std::string text;
  for (int i = 1; i <= 2000; ++i) {
    text += odom(std::to_string(i) + " 0 0", std::to_string(i));
    std::vector<std::string> ranges;
    for (int k = 0; k < 181; ++k)
      ranges.push_back(std::to_string((i * 7919 + k * 104729) % 5000));
    text += flaser(ranges, "0 0 0 0 0 0", std::to_string(i) + ".5");
  }
  write_file(dir / "run.log", text);
  ASSERT_EQ(run_command("gzip -kf '" + (dir / "run.log").string() + "'").status, 0);
  const std::string bytes = read_file(dir / "run.log.gz");
  write_file(dir / "cut.log.gz", bytes.substr(0, bytes.size() * 2 / 3));
  const long complete = std::stol(
      run_command("zcat '" + (dir / "cut.log.gz").string() + "' 2>/dev/null | wc -l").out);
  const InputError error = catch_input_error([&] { read_carmen_log(dir / "cut.log.gz"); });
  expect_located(error, dir / "cut.log.gz", complete + 1, "");
}

TEST(CarmenLogErrorTest, LogWithoutLaserScansIsAnError) {
  TempDir dir;
  expect_located(read_bad(dir, "PARAM a b\n" + odom("0 0 0", "1") + odom("0 0 0", "2")),
                 dir / "bad.log", 3, "");
}

TEST(CarmenLogTest, LogWithEveryScanTimestampZeroIsReadInLineOrderWithAWarning) {
  TempDir dir;
  // Orebro's log is written so: every FLASER and ODOM stamped 0.
  const CarmenLog log =
      read_text(dir, odom("1 0 0", "0") + flaser({"1", "2", "3"}, "1 0 0 1 0 0", "0") +
                         odom("2 0 0", "0") + flaser({"1", "2", "3"}, "2 0 0 2 0 0", "0") +
                         flaser({"1", "2", "3"}, "3 0 0 3 0 0", "0"));
  ASSERT_EQ(log.scans.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(log.scans[i].robot_pose.x, double(i + 1));  // in line order
  EXPECT_EQ(log.odometry.size(), 2u);
  EXPECT_EQ(log.summary.messages.at("FLASER").kept, 3u);
  EXPECT_EQ(log.summary.messages.at("FLASER").skipped_zero_timestamp, 0u);
  ASSERT_EQ(log.summary.warnings.size(), 1u);
  EXPECT_NE(log.summary.warnings[0].find("line order"), std::string::npos);

  // With one valid timestamp, the zero ones are skipped as before, without a warning.
  const CarmenLog mixed = read_text(dir, flaser_of(2, "0") + flaser_of(2, "5") + flaser_of(2, "0"));
  EXPECT_EQ(mixed.scans.size(), 1u);
  EXPECT_EQ(mixed.summary.messages.at("FLASER").skipped_zero_timestamp, 2u);
  EXPECT_TRUE(mixed.summary.warnings.empty());
}

// `count` scans of 100 beams: `long_beams` of them at `long_range`, the rest at 3 m.
std::string scans_with_long_readings(int count, int long_beams, const std::string& long_range,
                                     int first_stamp = 1) {
  std::string text;
  for (int i = 0; i < count; ++i) {
    std::vector<std::string> ranges(100, "3");
    for (int b = 0; b < long_beams; ++b)
      ranges[static_cast<std::size_t>(b)] = long_range;
    text += flaser(ranges, "0 0 0 0 0 0", std::to_string(first_stamp + i));
  }
  return text;
}

TEST(CarmenLogTest, ReadingsBeyondAParamMaxRangeWinOverIt) {
  TempDir dir;
  // PARAM says 10 m, but readings spread to 51 m: they are real, the PARAM is wrong.
  std::string text = "PARAM robot_front_laser_max 10 0 h 0\n";
  for (int i = 0; i < 50; ++i) {
    std::vector<std::string> ranges(100, "3");
    for (int b = 0; b < 10; ++b)
      ranges[static_cast<std::size_t>(b)] = std::to_string(11 + (i * 10 + b) % 41);  // 11..51
    text += flaser(ranges, "0 0 0 0 0 0", std::to_string(i + 1));
  }
  const CarmenLog log = read_text(dir, text);
  ASSERT_EQ(log.summary.laser_configs.size(), 1u);
  const UsedSetting& max_range = log.summary.laser_configs[0].max_range;
  EXPECT_EQ(max_range.source, SettingSource::readings);
  EXPECT_GT(max_range.value, 51.0);  // every reading, 51 m included, is a hit
  EXPECT_EQ(log.scans[0].max_range, max_range.value);
  EXPECT_EQ(log.summary.ranges.no_return, 0u);
  ASSERT_EQ(log.summary.warnings.size(), 1u);
  EXPECT_NE(log.summary.warnings[0].find("robot_front_laser_max"), std::string::npos);
  EXPECT_NE(log.summary.warnings[0].find("the readings win"), std::string::npos);

  // The manifest's max range is never overruled.
  CarmenReadOptions options;
  options.laser.max_range = 10.0;
  const CarmenLog kept = read_text(dir, text, options);
  EXPECT_EQ(kept.summary.laser_configs[0].max_range.value, 10.0);
  EXPECT_TRUE(kept.summary.warnings.empty());
}

TEST(CarmenLogTest, ReadingsSaturatingBelowTheGuessAreNoReturns) {
  TempDir dir;
  // 5% of the readings at exactly 32.767 m (Orebro's no-return code), under the 80 m guess.
  const CarmenLog log = read_text(dir, scans_with_long_readings(40, 5, "32.767"));
  const UsedSetting& max_range = log.summary.laser_configs.at(0).max_range;
  EXPECT_EQ(max_range.source, SettingSource::readings);
  EXPECT_EQ(static_cast<float>(max_range.value), 32.767f);
  EXPECT_EQ(log.summary.ranges.no_return, 200u);
  // A few long readings are hits, not a saturation code: the guess stands.
  const CarmenLog few = read_text(
      dir, scans_with_long_readings(40, 1, "32.767") + scans_with_long_readings(400, 0, "3", 100));
  EXPECT_EQ(few.scans.size(), 440u);
  EXPECT_EQ(few.summary.laser_configs.at(0).max_range.source, SettingSource::guess);
  EXPECT_TRUE(few.summary.warnings.empty());
  // Long readings at or above a PARAM's max range, all in one cluster, agree with it.
  const CarmenLog agree = read_text(
      dir, "PARAM robot_front_laser_max 80.99 0 h 0\n" + scans_with_long_readings(40, 5, "81.91"));
  EXPECT_EQ(agree.summary.laser_configs.at(0).max_range.source, SettingSource::param);
  EXPECT_EQ(agree.summary.ranges.no_return, 200u);
}

TEST(CarmenLogErrorTest, BadLaserParamValueNamesIt) {
  TempDir dir;
  expect_located(read_bad(dir, "PARAM laser_front_laser_resolution fast 0 h 0\n"), dir / "bad.log",
                 1, "value");
  expect_located(read_bad(dir, "# x\nPARAM robot_front_laser_max -5 0 h 0\n"), dir / "bad.log", 2,
                 "value");
  expect_located(read_bad(dir, "PARAM lonely\n"), dir / "bad.log", 1, "value");
}

TEST(CarmenLogErrorTest, BadRobotLaserSettingNamesIt) {
  TempDir dir;
  expect_located(read_bad(dir,
                          "ROBOTLASER1 0 -2.0 3.0 0 30.0 0.01 0 2 1.0 2.0 0 "
                          "0 0 0 0 0 0 0 0 0 0 0 2 h 2\n"),
                 dir / "bad.log", 1, "angular_resolution");
}

TEST(CarmenLogErrorTest, BinaryFileIsNotACarmenLog) {
  TempDir dir;
  expect_located(read_bad(dir, std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)), dir / "bad.log",
                 1, "type");
}

TEST(CarmenLogErrorTest, BadManifestSettingNamesTheField) {
  TempDir dir;
  write_file(dir / "ok.log", flaser_of(2, "1"));
  CarmenReadOptions options;
  options.laser.max_range = -1.0;
  const InputError error = catch_input_error([&] { read_carmen_log(dir / "ok.log", options); });
  EXPECT_EQ(error.field(), "laser.max_range");
  options.laser.max_range = 10.0;
  options.laser.min_range = 20.0;
  EXPECT_EQ(catch_input_error([&] { read_carmen_log(dir / "ok.log", options); }).field(),
            "laser.min_range");
}

// ---- the real logs: every expected number comes from zcat/grep/awk, not from the reader ----

long count_of(const std::string& command) {
  const auto result = run_command(command);
  EXPECT_EQ(result.err, "");
  return std::stol(result.out);
}

long grep_count(const std::filesystem::path& file, const std::string& pattern) {
  return count_of("zcat '" + file.string() + "' | grep -c '" + pattern + "'");
}

struct TimestampTruth {
  long kept = 0, zero = 0, backwards = 0, equal = 0;
  double first = 0.0, last = 0.0;
};

// awk's count of one type's kept, zero (<= 0) and backwards timestamps, by the rule of SPEC.md;
// `field` is the awk expression of the timestamp.
TimestampTruth timestamp_truth(const std::filesystem::path& file, const std::string& type,
                               const std::string& field) {
  const std::string program =
      "$1==\"" + type + "\" { t=" + field +
      "+0; if (t<=0) z++; else if (n && t<last) b++; else { if (n && t==last) e++; "
      "if (!n) first=t; n++; last=t } } END { printf \"%d %d %d %d %.17g %.17g\\n\", n, z, b, e, "
      "first, last }";
  const auto result = run_command("zcat '" + file.string() + "' | awk '" + program + "'");
  TimestampTruth truth;
  std::istringstream(result.out) >> truth.kept >> truth.zero >> truth.backwards >> truth.equal >>
      truth.first >> truth.last;
  return truth;
}

void expect_counts_match(const CarmenLog& log, const std::string& type, const TimestampTruth& truth,
                         long grep_lines) {
  const MessageTypeCount& count = log.summary.messages.at(type);
  EXPECT_EQ(static_cast<long>(count.lines), grep_lines) << type;
  EXPECT_EQ(static_cast<long>(count.kept), truth.kept) << type;
  EXPECT_EQ(static_cast<long>(count.skipped_zero_timestamp), truth.zero) << type;
  EXPECT_EQ(static_cast<long>(count.skipped_backwards_timestamp), truth.backwards) << type;
  EXPECT_EQ(count.kept + count.skipped_zero_timestamp + count.skipped_backwards_timestamp,
            count.lines)
      << type;
}

long ranges_at_or_above(const std::filesystem::path& file, double max_range) {
  return count_of("zcat '" + file.string() +
                  "' | awk '$1==\"FLASER\" { for (i = 3; i < 3 + $2; i++) if ($i + 0 >= " +
                  std::to_string(max_range) + ") c++ } END { print c + 0 }'");
}

TEST(CarmenRealLogTest, Fr079Has4791ScansOf360BeamsAtHalfADegree) {
  FLOORGRID_REQUIRE_DATA("fr079/freiburg-079-corrected.log.gz");
  const auto file = data_path("fr079/freiburg-079-corrected.log.gz");
  const CarmenLog log = read_carmen_log(file);  // speed is measured in bench/, not here

  const long flaser_lines = grep_count(file, "^FLASER ");
  EXPECT_EQ(flaser_lines, 4791);
  EXPECT_EQ(static_cast<long>(log.scans.size()), flaser_lines);
  EXPECT_EQ(count_of("zcat '" + file.string() +
                     "' | awk '$1==\"FLASER\" && $2==360 && NF==371' "
                     "| wc -l"),
            flaser_lines);
  ASSERT_EQ(log.summary.beams_per_scan.size(), 1u);
  EXPECT_EQ(static_cast<long>(log.summary.beams_per_scan.at(360)), flaser_lines);
  ASSERT_EQ(log.summary.laser_configs.size(), 1u);
  const LaserConfigUsage& config = log.summary.laser_configs[0];
  EXPECT_EQ(config.angle_increment.value, pi / 360);
  EXPECT_EQ(config.angle_increment.source, SettingSource::param);
  EXPECT_EQ(config.angle_increment.detail, "laser_front_laser_resolution");
  // The log has no laser_front_laser_maxrange; CARMEN's robot_front_laser_max says 80.99.
  EXPECT_EQ(
      count_of("zcat '" + file.string() + "' | grep -c '^PARAM robot_front_laser_max 80.99 '"), 1);
  EXPECT_EQ(config.max_range.value, 80.99);
  EXPECT_EQ(config.max_range.source, SettingSource::param);

  const TimestampTruth odometry = timestamp_truth(file, "ODOM", "$8");
  expect_counts_match(log, "ODOM", odometry, grep_count(file, "^ODOM "));
  EXPECT_EQ(static_cast<long>(log.odometry.size()), odometry.kept);
  const TimestampTruth scans = timestamp_truth(file, "FLASER", "$($2+9)");
  expect_counts_match(log, "FLASER", scans, flaser_lines);
  EXPECT_EQ(log.summary.messages.at("NEFF").lines,
            static_cast<std::size_t>(grep_count(file, "^NEFF")));
  EXPECT_EQ(log.summary.messages.at("PARAM").lines,
            static_cast<std::size_t>(grep_count(file, "^PARAM ")));
  EXPECT_EQ(log.summary.messages.at("#").lines, static_cast<std::size_t>(grep_count(file, "^#")));
  EXPECT_EQ(log.summary.lines, static_cast<std::size_t>(grep_count(file, "")));

  EXPECT_EQ(static_cast<long>(log.summary.ranges.no_return), ranges_at_or_above(file, 80.99));
  EXPECT_EQ(log.summary.ranges.total, 4791u * 360u);
  EXPECT_EQ(log.summary.first_timestamp, std::min(odometry.first, scans.first));
  EXPECT_EQ(log.summary.last_timestamp, std::max(odometry.last, scans.last));

  // The first scan, number by number, against the text as the C library parses it.
  const auto first = run_command("zcat '" + file.string() + "' | grep -m1 '^FLASER '");
  std::istringstream fields(first.out);
  std::string word;
  fields >> word >> word;
  for (std::size_t i = 0; i < 360; ++i) {
    fields >> word;
    ASSERT_EQ(log.scans[0].ranges[i], static_cast<float>(std::strtod(word.c_str(), nullptr)));
  }
  double value = 0.0;
  fields >> value;
  EXPECT_EQ(log.scans[0].laser_pose.x, value);
}

TEST(CarmenRealLogTest, AcesHas440ScansOf180BeamsAtOneDegreeByGuess) {
  FLOORGRID_REQUIRE_DATA("carmen/aces-corrected.log.gz");
  const auto file = data_path("carmen/aces-corrected.log.gz");
  const CarmenLog log = read_carmen_log(file);
  EXPECT_EQ(grep_count(file, "^FLASER "), 440);
  EXPECT_EQ(log.scans.size(), 440u);
  EXPECT_EQ(count_of("zcat '" + file.string() + "' | awk '$1==\"FLASER\" && $2==180' | wc -l"),
            440);
  ASSERT_EQ(log.summary.laser_configs.size(), 1u);
  const LaserConfigUsage& config = log.summary.laser_configs[0];
  EXPECT_EQ(config.beams, 180u);
  EXPECT_EQ(config.angle_increment.value, pi / 180);
  EXPECT_EQ(config.angle_increment.source, SettingSource::guess);
  EXPECT_EQ(count_of("zcat '" + file.string() +
                     "' | grep -c -e '_resolution' -e '_laser_max' "
                     "-e 'maxrange' || true"),
            0);
  expect_counts_match(log, "ODOM", timestamp_truth(file, "ODOM", "$8"), grep_count(file, "^ODOM "));
  expect_counts_match(log, "FLASER", timestamp_truth(file, "FLASER", "$($2+9)"), 440);
  // ACES saturates at 50 m, below the 80 m guess: the readings win, those are no returns.
  EXPECT_EQ(config.max_range.source, SettingSource::readings);
  EXPECT_NEAR(config.max_range.value, 50.0, 0.1);
  EXPECT_GE(static_cast<long>(log.summary.ranges.no_return), ranges_at_or_above(file, 50.0));
  EXPECT_LE(static_cast<long>(log.summary.ranges.no_return), ranges_at_or_above(file, 49.9));
  EXPECT_EQ(log.summary.warnings.size(), 1u);

  // A manifest's 50 m is used as given.
  CarmenReadOptions options;
  options.laser.max_range = 50.0;
  const CarmenLog capped = read_carmen_log(file, options);
  EXPECT_EQ(static_cast<long>(capped.summary.ranges.no_return), ranges_at_or_above(file, 50.0));
  EXPECT_GT(capped.summary.ranges.no_return, 0u);
  EXPECT_EQ(capped.summary.laser_configs[0].max_range.source, SettingSource::manifest);
}

TEST(CarmenRealLogTest, CsailHas406ScansOf361BeamsAndKeepsEqualTimestamps) {
  FLOORGRID_REQUIRE_DATA("carmen/csail-corrected.log.gz");
  const auto file = data_path("carmen/csail-corrected.log.gz");
  const CarmenLog log = read_carmen_log(file);
  EXPECT_EQ(grep_count(file, "^FLASER "), 406);
  EXPECT_EQ(log.scans.size(), 406u);
  EXPECT_EQ(count_of("zcat '" + file.string() + "' | awk '$1==\"FLASER\" && $2==361' | wc -l"),
            406);
  const LaserConfigUsage& config = log.summary.laser_configs.at(0);
  EXPECT_EQ(log.summary.laser_configs.size(), 1u);
  EXPECT_EQ(config.beams, 361u);
  EXPECT_EQ(config.angle_increment.value, pi / 360);
  EXPECT_EQ(config.angle_increment.source, SettingSource::param);
  EXPECT_EQ(config.max_range.value, 50.0);  // PARAM robot_front_laser_max 50
  EXPECT_EQ(config.max_range.source, SettingSource::param);
  const TimestampTruth scans = timestamp_truth(file, "FLASER", "$($2+9)");
  EXPECT_GT(scans.equal, 400);  // printed to 6 digits: nearly all equal, and all kept
  expect_counts_match(log, "FLASER", scans, 406);
  const TimestampTruth odometry = timestamp_truth(file, "ODOM", "$8");
  EXPECT_GT(odometry.equal, 1000);
  expect_counts_match(log, "ODOM", odometry, grep_count(file, "^ODOM "));
  EXPECT_EQ(static_cast<long>(log.summary.ranges.no_return), ranges_at_or_above(file, 50.0));
}

}  // namespace
}  // namespace floorgrid::io
