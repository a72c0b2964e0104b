#include "floorgrid/io/formats/pairs_csv.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::io {
namespace {

using test::expect_input_error;
using test::TempDir;
using test::write_file;

TEST(PairsCsv, ReadsMetresWeightsAndUnits) {
  TempDir dir;
  write_file(dir / "p.csv",
             "\xEF\xBB\xBFplan_x,plan_y,grid_x,grid_y,weight\r\n# a comment\r\n1,2,3,4,0.5\r\n"
             "\r\n-1.5e1, 0.25 ,+7,8,2\r\n");
  const ReferencePairs p = read_pairs_csv(dir / "p.csv");
  ASSERT_EQ(p.size(), 2);
  EXPECT_EQ(p.points_in_plan(0, 0), 1.0);
  EXPECT_EQ(p.points_in_grid(1, 0), 4.0);
  EXPECT_EQ(p.points_in_plan(0, 1), -15.0);
  EXPECT_EQ(p.points_in_plan(1, 1), 0.25);
  EXPECT_EQ(p.points_in_grid(0, 1), 7.0);
  EXPECT_EQ(p.weight(0), 0.5);
  EXPECT_EQ(p.weight(1), 2.0);
  const ReferencePairs px = read_pairs_csv(dir / "p.csv", 0.05);
  EXPECT_DOUBLE_EQ(px.points_in_grid(0, 1), 7.0 * 0.05);
  EXPECT_EQ(px.weight(1), 2.0);  // weights are not lengths
}

TEST(PairsCsv, WriteThenReadIsExact) {
  ReferencePairs p;
  p.points_in_plan = Eigen::Matrix2Xd::Random(2, 50) * 123.456;
  p.points_in_grid = Eigen::Matrix2Xd::Random(2, 50) * 1e-3;
  TempDir dir;
  write_pairs_csv(p, dir / "p.csv");
  const ReferencePairs back = read_pairs_csv(dir / "p.csv");
  EXPECT_EQ(back.points_in_plan, p.points_in_plan);
  EXPECT_EQ(back.points_in_grid, p.points_in_grid);
  EXPECT_FALSE(back.has_weights());
  EXPECT_EQ(test::read_file(dir / "p.csv").substr(0, 28), "plan_x,plan_y,grid_x,grid_y\n");
}

TEST(PairsCsv, RealHalmstadPairsRead) {
  FLOORGRID_REQUIRE_DATA("halmstad/E5/pairs");
  std::size_t total = 0, lines = 0;
  for (const auto& env : {"E5", "F5", "HIH"}) {
    for (const auto& entry : std::filesystem::directory_iterator(
             test::data_path(std::string("halmstad/") + env + "/pairs"))) {
      total += static_cast<std::size_t>(read_pairs_csv(entry.path(), 0.05).size());
      std::ifstream in(entry.path());
      std::string line;
      while (std::getline(in, line))
        lines += line.empty() ? 0 : 1;
      --lines;  // header
    }
  }
  EXPECT_EQ(total, lines);
  EXPECT_GT(total, 500u);
}

TEST(PairsCsv, BadFilesNameFileLineAndColumn) {
  TempDir dir;
  const auto check = [&](const std::string& name, const std::string& text,
                         const std::vector<std::string>& parts) {
    write_file(dir / name, text);
    auto expected = parts;
    expected.push_back(name);
    expect_input_error([&] { read_pairs_csv(dir / name); }, expected);
  };
  check("header.csv", "x,y,u,v\n1,2,3,4\n", {":1:", "plan_x"});
  check("short.csv", "plan_x,plan_y,grid_x,grid_y\n1,2,3,4\n1,2,3\n", {":3:", "expected 4"});
  check("long.csv", "plan_x,plan_y,grid_x,grid_y\n1,2,3,4,5\n", {":2:", "expected 4"});
  check("number.csv", "plan_x,plan_y,grid_x,grid_y\n1,2,x3,4\n", {":2:", "'grid_x'", "x3"});
  check("nan.csv", "plan_x,plan_y,grid_x,grid_y\n1,nan,3,4\n", {":2:", "'plan_y'", "finite"});
  check("weight.csv", "plan_x,plan_y,grid_x,grid_y,weight\n1,2,3,4,-1\n", {":2:", "'weight'"});
  check("empty.csv", "", {"empty"});
  check("nopairs.csv", "plan_x,plan_y,grid_x,grid_y\n", {"no pairs"});
  check("truncated.csv", "plan_x,plan_y,grid_x,grid_y\n1,2,3,4\n5,6,7", {":3:", "expected 4"});
  expect_input_error([&] { read_pairs_csv(dir / "missing.csv"); }, {"missing.csv", "no such"});
  expect_input_error([&] { read_pairs_csv(dir / "long.csv", -1.0); }, {"'unit'"});
}

}  // namespace
}  // namespace floorgrid::io
