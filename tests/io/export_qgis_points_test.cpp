// QGIS Georeferencer .points: rows of a known similarity, by hand.
#include "floorgrid/io/export/export_qgis_points.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "floorgrid/core/error.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;

std::vector<std::vector<double>> rows_of(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ','))
      row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

TEST(ExportQgisPoints, RowsOfAKnownSimilarityInRasterPixels) {
  const KnownSimilarity truth{1.5, 0.3, {2.0, -1.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 16, 0, 8));
  // Two pairs: one exact, one whose grid point is off by (0.1, -0.2).
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 2);
  pairs.points_in_grid.resize(2, 2);
  pairs.points_in_plan << 3.0, 5.5, 4.0, 1.25;
  pairs.points_in_grid.col(0) = truth({3.0, 4.0});
  pairs.points_in_grid.col(1) = truth({5.5, 1.25}) + Eigen::Vector2d(0.1, -0.2);
  // The plan raster: 200 x 100 pixels of 0.1 m, origin (-1, -2).
  GridGeometry raster;
  raster.width = 200;
  raster.height = 100;
  raster.resolution = 0.1;
  raster.origin = {-1.0, -2.0, 0.0};
  const io::QgisPoints points = io::qgis_points(*model, pairs, raster);
  EXPECT_EQ(points.text.rfind("#CRS: \nmapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n", 0), 0u)
      << points.text;
  EXPECT_TRUE(points.source_in_pixels);
  ASSERT_EQ(points.points, 2u);
  const auto rows = rows_of(points.text);
  ASSERT_EQ(rows.size(), 2u);
  // Plan (3, 4): pixel x = (3 + 1) / 0.1 = 40, line = 100 - (4 + 2) / 0.1 = 40, QGIS y = -40.
  const Eigen::Vector2d g0 = truth({3.0, 4.0});
  EXPECT_NEAR(rows[0][0], g0.x(), 1e-9);
  EXPECT_NEAR(rows[0][1], g0.y(), 1e-9);
  EXPECT_NEAR(rows[0][2], 40.0, 1e-9);
  EXPECT_NEAR(rows[0][3], -40.0, 1e-9);
  EXPECT_EQ(rows[0][4], 1.0);
  EXPECT_NEAR(rows[0][5], 0.0, 1e-9);
  EXPECT_NEAR(rows[0][6], 0.0, 1e-9);
  EXPECT_NEAR(rows[0][7], 0.0, 1e-9);
  // Plan (5.5, 1.25): x = 65, line = 100 - 32.5 = 67.5; residual model - grid = (-0.1, 0.2).
  EXPECT_NEAR(rows[1][2], 65.0, 1e-9);
  EXPECT_NEAR(rows[1][3], -67.5, 1e-9);
  EXPECT_NEAR(rows[1][5], -0.1, 1e-9);
  EXPECT_NEAR(rows[1][6], 0.2, 1e-9);
  EXPECT_NEAR(rows[1][7], std::hypot(0.1, 0.2), 1e-9);
  EXPECT_NEAR(points.rms_m, std::sqrt(0.05 / 2.0), 1e-9);
}

TEST(ExportQgisPoints, WithoutARasterTheSourceIsPlanMetres) {
  const KnownSimilarity truth{1.0, -0.7, {10.0, 3.0}};
  const auto model = test::fitted("gt-rigid", test::lattice_pairs(truth, 0, 16, 0, 8));
  const ReferencePairs pairs = test::lattice_pairs(truth, 1, 3, 2, 4, 2, 2);
  const io::QgisPoints points = io::qgis_points(*model, pairs, std::nullopt);
  EXPECT_FALSE(points.source_in_pixels);
  const auto rows = rows_of(points.text);
  ASSERT_EQ(rows.size(), 4u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    EXPECT_NEAR(rows[i][2], pairs.points_in_plan(0, c), 1e-12);
    EXPECT_NEAR(rows[i][3], pairs.points_in_plan(1, c), 1e-12);
    EXPECT_NEAR(rows[i][0], pairs.points_in_grid(0, c), 1e-12);
    EXPECT_NEAR(rows[i][7], 0.0, 1e-9);
  }
}

TEST(ExportQgisPoints, ManyPairsAreBinnedToTheBudget) {
  const KnownSimilarity truth{1.0, 0.0, {0.0, 0.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 40, 0, 40));
  const ReferencePairs pairs = test::lattice_pairs(truth, 0, 40, 0, 40, 60, 50);
  io::QgisPointsOptions options;
  options.max_points = 200;
  const io::QgisPoints points = io::qgis_points(*model, pairs, std::nullopt, options);
  EXPECT_EQ(points.pairs, 3000u);
  EXPECT_LE(points.points, 200u);
  EXPECT_GE(points.points, 100u);
  EXPECT_EQ(rows_of(points.text).size(), points.points);
}

TEST(ExportQgisPoints, RefusesNoPairsAndATinyBudget) {
  const KnownSimilarity truth{1.0, 0.0, {0.0, 0.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 4, 0, 4));
  EXPECT_THROW(io::qgis_points(*model, ReferencePairs{}, std::nullopt), InputError);
  io::QgisPointsOptions options;
  options.max_points = 2;
  EXPECT_THROW(
      io::qgis_points(*model, test::lattice_pairs(truth, 0, 4, 0, 4), std::nullopt, options),
      InputError);
}

}  // namespace
}  // namespace floorgrid
