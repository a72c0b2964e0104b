// GDAL VRT: GCPs of a known similarity by hand, and GDAL's own transformers reading them back
// (gdaltransform and gdalinfo from Debian's gdal-bin, a test tool only).
#include "floorgrid/io/export/export_gdal_vrt.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;
using test::quoted;
using test::TempDir;

/// A 200 x 100 raster of 0.1 m pixels, origin (-1, -2), written as a PGM.
io::MapRaster plan_raster(const TempDir& dir, double yaw = 0.0) {
  io::MapRaster raster;
  raster.image = dir / "plan.pgm";
  raster.geometry.width = 200;
  raster.geometry.height = 100;
  raster.geometry.resolution = 0.1;
  raster.geometry.origin = {-1.0, -2.0, yaw};
  std::vector<std::uint8_t> pixels(200 * 100, 254);
  for (int x = 0; x < 200; ++x)
    pixels[static_cast<std::size_t>(50 * 200 + x)] = 0;
  io::write_pgm(raster.image, 200, 100, pixels);
  return raster;
}

/// gdaltransform's output for pixel/line `points` through the VRT with `transformer`.
std::vector<Eigen::Vector2d> gdaltransform(const std::filesystem::path& vrt,
                                           const std::string& transformer,
                                           const std::vector<Eigen::Vector2d>& points,
                                           const TempDir& dir) {
  std::string input;
  for (const Eigen::Vector2d& p : points)
    input += fmt::format("{} {}\n", p.x(), p.y());
  test::write_file(dir / "input.txt", input);
  const auto run = test::run_command("gdaltransform " + transformer + " " + quoted(vrt) + " < " +
                                     quoted(dir / "input.txt"));
  EXPECT_EQ(run.status, 0) << run.err;
  std::vector<Eigen::Vector2d> out;
  std::istringstream lines(run.out);
  double x = 0, y = 0, z = 0;
  while (lines >> x >> y >> z)
    out.emplace_back(x, y);
  EXPECT_EQ(out.size(), points.size()) << run.out << run.err;
  return out;
}

std::vector<Eigen::Vector2d> random_pixels(int n, double width, double height) {
  Random random(7);
  std::vector<Eigen::Vector2d> points = {{0, 0}, {width, height}, {0.5, 0.5}};
  for (int i = 0; i < n; ++i)
    points.emplace_back(random.uniform(0, width), random.uniform(0, height));
  return points;
}

TEST(ExportGdalVrt, GcpsOfAKnownSimilarityByHand) {
  TempDir dir;
  const KnownSimilarity truth{2.0, M_PI / 2, {1.0, 2.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 16, 0, 8));
  const io::MapRaster raster = plan_raster(dir);
  const io::GdalVrt vrt = io::gdal_vrt(*model, raster, io::VrtSource::plan, dir / "plan.vrt");
  EXPECT_TRUE(vrt.exact);
  EXPECT_EQ(vrt.transformer, "-order 1");
  ASSERT_EQ(vrt.gcps.size(), 9u);
  // Pixel/line (0, 0) is the image's top-left corner: plan (-1, -2 + 100 x 0.1) = (-1, 8);
  // grid = 2 R90 (-1, 8) + (1, 2) = 2 (-8, -1) + (1, 2) = (-15, 0).
  EXPECT_DOUBLE_EQ(vrt.gcps[0].pixel, 0.0);
  EXPECT_DOUBLE_EQ(vrt.gcps[0].line, 0.0);
  EXPECT_NEAR(vrt.gcps[0].x, -15.0, 1e-9);
  EXPECT_NEAR(vrt.gcps[0].y, 0.0, 1e-9);
  // (200, 100): the bottom-right corner, plan (19, -2): grid 2 (2, 19) + (1, 2) = (5, 40).
  EXPECT_DOUBLE_EQ(vrt.gcps[8].pixel, 200.0);
  EXPECT_DOUBLE_EQ(vrt.gcps[8].line, 100.0);
  EXPECT_NEAR(vrt.gcps[8].x, 5.0, 1e-9);
  EXPECT_NEAR(vrt.gcps[8].y, 40.0, 1e-9);
  EXPECT_NE(vrt.text.find("<SourceFilename relativeToVRT=\"1\">plan.pgm</SourceFilename>"),
            std::string::npos)
      << vrt.text;
  EXPECT_NE(vrt.text.find("rasterXSize=\"200\" rasterYSize=\"100\""), std::string::npos);
}

TEST(ExportGdalVrt, GdaltransformOrderOneReproducesASimilarityWithinAMillimetre) {
  if (!test::have_program("gdaltransform") || !test::have_program("gdalinfo"))
    GTEST_SKIP() << "gdaltransform/gdalinfo (Debian gdal-bin) not installed";
  TempDir dir;
  const KnownSimilarity truth{1.7, -0.4, {12.0, -3.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 16, 0, 8));
  const io::MapRaster raster = plan_raster(dir, 0.2);  // a rotated plan YAML too
  const auto path = dir / "plan.vrt";
  io::write_file_atomically(path, io::gdal_vrt(*model, raster, io::VrtSource::plan, path).text);
  const auto info = test::run_command("gdalinfo " + quoted(path));
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("Size is 200, 100"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("GCP[  8]"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("FLOORGRID_GDAL_TRANSFORMER=-order 1"), std::string::npos) << info.out;
  const auto pixels = random_pixels(50, 200, 100);
  const auto mapped = gdaltransform(path, "-order 1", pixels, dir);
  ASSERT_EQ(mapped.size(), pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    // By hand: image (u, v) -> plan origin + R(yaw) 0.1 (u, 100 - v) -> truth.
    const Eigen::Vector2d plan =
        Eigen::Vector2d(-1.0, -2.0) +
        rotation_2d(0.2) * (0.1 * Eigen::Vector2d(pixels[i].x(), 100.0 - pixels[i].y()));
    EXPECT_LT((mapped[i] - truth(plan)).norm(), 1e-3) << pixels[i].transpose();
    EXPECT_LT((mapped[i] - model->forward(plan)).norm(), 1e-3) << pixels[i].transpose();
  }
}

TEST(ExportGdalVrt, GridmapSourceMapsIntoThePlanThroughTheInverse) {
  if (!test::have_program("gdaltransform"))
    GTEST_SKIP() << "gdaltransform (Debian gdal-bin) not installed";
  TempDir dir;
  const KnownSimilarity truth{0.8, 2.5, {-4.0, 6.0}};
  const auto model = test::fitted("gt-affine", test::lattice_pairs(truth, 0, 16, 0, 8));
  const io::MapRaster raster = plan_raster(dir);
  const auto path = dir / "grid.vrt";
  const io::GdalVrt vrt = io::gdal_vrt(*model, raster, io::VrtSource::gridmap, path);
  EXPECT_TRUE(vrt.exact);
  io::write_file_atomically(path, vrt.text);
  const auto pixels = random_pixels(30, 200, 100);
  const auto mapped = gdaltransform(path, "-order 1", pixels, dir);
  ASSERT_EQ(mapped.size(), pixels.size());
  const Eigen::Matrix2d R_inverse = rotation_2d(-2.5) / 0.8;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector2d grid =
        Eigen::Vector2d(-1.0, -2.0) + 0.1 * Eigen::Vector2d(pixels[i].x(), 100.0 - pixels[i].y());
    const Eigen::Vector2d plan = R_inverse * (grid - truth.t);
    EXPECT_LT((mapped[i] - plan).norm(), 1e-3) << pixels[i].transpose();
  }
}

TEST(ExportGdalVrt, ThinPlateSplineFollowsANonRigidModel) {
  if (!test::have_program("gdaltransform"))
    GTEST_SKIP() << "gdaltransform (Debian gdal-bin) not installed";
  TempDir dir;
  const test::BentTruth truth{{1.0, 0.3, {2.0, 1.0}}};
  const auto model = test::fitted("tps", test::lattice_pairs(truth, -1, 19, -2, 8, 21, 11));
  const io::MapRaster raster = plan_raster(dir);
  const auto path = dir / "plan.vrt";
  const io::GdalVrt vrt = io::gdal_vrt(*model, raster, io::VrtSource::plan, path);
  EXPECT_FALSE(vrt.exact);
  EXPECT_EQ(vrt.transformer, "-tps");
  EXPECT_EQ(vrt.gcps.size(), 33u * 33u);
  io::write_file_atomically(path, vrt.text);
  const auto pixels = random_pixels(200, 200, 100);
  const auto mapped = gdaltransform(path, "-tps", pixels, dir);
  ASSERT_EQ(mapped.size(), pixels.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector2d plan = io::image_to_frame(raster.geometry, pixels[i]);
    worst = std::max(worst, (mapped[i] - model->forward(plan)).norm());
  }
  // The stated tolerance of the -tps reproduction (README, --help): 1 cm.
  EXPECT_LT(worst, 0.01);
  RecordProperty("worst_tps_error_m", std::to_string(worst));
  std::cout << "worst -tps deviation from the model: " << worst << " m\n";
}

TEST(ExportGdalVrt, RefusesAnAsciiPgm) {
  TempDir dir;
  test::write_file(dir / "plan.pgm", "P2\n2 2\n255\n0 0\n0 0\n");
  io::MapRaster raster;
  raster.image = dir / "plan.pgm";
  raster.geometry.width = raster.geometry.height = 2;
  const KnownSimilarity truth{1.0, 0.0, {0.0, 0.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 4, 0, 4));
  EXPECT_THROW(io::gdal_vrt(*model, raster, io::VrtSource::plan, dir / "a.vrt"), InputError);
}

}  // namespace
}  // namespace floorgrid
