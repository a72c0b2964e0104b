#include "floorgrid/io/formats/scans_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

std::vector<std::string> lines_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

TEST(ScansCsv, OneRowPerScanWithEachFiltersPoseStateAndFit) {
  RobotLog log;
  log.scans.resize(2);
  log.scans[0].timestamp = 10.5;
  log.scans[1].timestamp = 11.25;
  DualLocalization l;
  l.scans.resize(2);
  l.scans[0].scan = 0;
  l.scans[0].plan.state = FilterState::global;
  l.scans[0].plan.fit = std::numeric_limits<double>::quiet_NaN();
  l.scans[0].grid.state = FilterState::global;
  l.scans[0].grid.fit = 0.125;
  l.scans[1].scan = 1;
  l.scans[1].plan.state = FilterState::tracking;
  l.scans[1].plan.converged = true;
  l.scans[1].plan.pose = {1.5, -2.0, 0.25};
  l.scans[1].plan.fit = 0.75;
  l.scans[1].plan.estimate.scale = 1.5;
  l.scans[1].grid.state = FilterState::recovering;
  l.scans[1].grid.pose = {3.0, 4.0, -1.0};
  l.scans[1].grid.fit = 0.5;
  l.scans[1].consistent = false;
  l.scans[1].pairs = 17;
  // The plan's scan match was accepted (the pose pairs are made from); the gridmap's was not.
  l.scans[1].plan.matched = true;
  l.scans[1].plan.match.pose = {1.625, -2.125, 0.5};
  l.scans[1].grid.matched = true;
  l.scans[1].grid.match.failure = ScanMatchFailure::degenerate;
  l.scans[1].grid.match.pose = {9.0, 9.0, 9.0};
  test::TempDir dir;
  write_scans_csv(l, log, dir / "scans.csv");
  const std::vector<std::string> lines = lines_of(dir / "scans.csv");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0],
            "scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,plan_scale,"
            "grid_x,grid_y,grid_theta,grid_state,grid_converged,grid_fit,grid_scale,consistent,"
            "pairs,plan_matched_x,plan_matched_y,plan_matched_theta,grid_matched_x,"
            "grid_matched_y,grid_matched_theta");
  // No fit where the map could not tell, no matched pose where no match was accepted.
  EXPECT_EQ(lines[1], "0,10.5,0,0,0,global,0,,1,0,0,0,global,0,0.1250,1,1,0,,,,,,");
  EXPECT_EQ(lines[2],
            "1,11.25,1.5,-2,0.25,tracking,1,0.7500,1.5,3,4,-1,recovering,0,0.5000,1,0,17,"
            "1.625,-2.125,0.5,,,");
}

TEST(ScansCsv, TheGridTrackReadBackIsTheTrackingFiltersPosesAtTheirTimes) {
  RobotLog log;
  log.scans.resize(3);
  log.scans[0].timestamp = 5.0;
  log.scans[1].timestamp = 5.2;
  log.scans[2].timestamp = std::numeric_limits<double>::quiet_NaN();  // a log without one
  DualLocalization l;
  l.scans.resize(3);
  for (std::size_t i = 0; i < 3; ++i) {
    l.scans[i].scan = i;
    l.scans[i].grid.state = i == 0 ? FilterState::global : FilterState::tracking;
    l.scans[i].grid.pose = {0.5 + i, -1.25 * i, 0.1 * i};
  }
  test::TempDir dir;
  write_scans_csv(l, log, dir / "scans.csv");
  const std::vector<TimedPose> track = read_grid_track(dir / "scans.csv");
  ASSERT_EQ(track.size(), 2u);  // the global filter's mean is no pose
  EXPECT_DOUBLE_EQ(track[0].time, 5.2);
  EXPECT_TRUE(std::isnan(track[1].time));
  for (std::size_t k = 0; k < 2; ++k) {
    const Pose2& p = l.scans[k + 1].grid.pose;
    EXPECT_DOUBLE_EQ(track[k].pose_in_grid.x, p.x);
    EXPECT_DOUBLE_EQ(track[k].pose_in_grid.y, p.y);
    EXPECT_DOUBLE_EQ(track[k].pose_in_grid.theta, p.theta);
  }
}

TEST(ScansCsv, ABadTrackFileIsRefusedNamingTheFileLineAndColumn) {
  test::TempDir dir;
  const auto refused = [&](const std::string& text, const std::string& says) {
    const std::filesystem::path file = dir / "scans.csv";
    std::ofstream(file) << text;
    try {
      read_grid_track(file);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string message =
          std::string(e.what()) + " | line " + std::to_string(e.line()) + " | " + e.field();
      EXPECT_NE(message.find("scans.csv"), std::string::npos) << message;
      EXPECT_NE(message.find(says), std::string::npos) << message;
    }
  };
  refused("", "empty file");
  refused("scan,time,grid_x,grid_y,grid_state\n", "grid_theta");
  refused("time,grid_x,grid_y,grid_theta,grid_state\n1,2,3\n", "line 2");
  refused("time,grid_x,grid_y,grid_theta,grid_state\n1,2,x,0,tracking\n", "grid_y");
}

}  // namespace
}  // namespace floorgrid::io
