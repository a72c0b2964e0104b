// `floorgrid export` end to end on a small hand-made dataset (no log: maps only).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>

#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/plans/dxf_writer.hpp"
#include "tests/io/export_test_support.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::read_file;
using test::run_floorgrid;
using test::TempDir;
using test::write_file;

const test::KnownSimilarity kTruth{1.0, 0.25, {3.0, -2.0}};

/// The room through kTruth.
VectorFloorplan room_in_grid() {
  VectorFloorplan grid;
  const VectorFloorplan room = test::asymmetric_room();
  for (const Segment& s : room.segments())
    grid.add_segment(kTruth(s.a), kTruth(s.b), "WALLS");
  return grid;
}

/// A dataset folder: plan (raster map YAML, or DXF), gridmap, and an `align`-like folder `al`
/// with the pairs and a gt model fitted by `floorgrid fit`.
void make_dataset(const TempDir& dir, bool dxf) {
  const VectorFloorplan room = test::asymmetric_room();
  if (dxf) {
    io::write_dxf(room, dir / "plan.dxf");
  } else {
    io::write_map(test::room_grid(room), dir / "plan.yaml");
  }
  io::write_map(test::room_grid(room_in_grid()), dir / "gridmap.yaml");
  write_file(dir / "dataset.yaml", std::string("floorplan: ") + (dxf ? "plan.dxf" : "plan.yaml") +
                                       "\nfloorplan_units: m\ngridmap: gridmap.yaml\n");
  fs::create_directories(dir / "al");
  io::write_pairs_csv(test::lattice_pairs(kTruth, 0, 12, 0, 8), dir / "al" / "pairs.csv");
  const auto fit = run_floorgrid("fit --pairs " + quoted(dir / "al" / "pairs.csv") +
                                 " --model gt --out " + quoted(dir / "al" / "model.json"));
  ASSERT_EQ(fit.status, 0) << fit.err;
}

std::string export_args(const TempDir& dir, const std::string& format, const std::string& out) {
  return "export --model " + quoted(dir / "al" / "model.json") + " --format " + format +
         " --dataset " + quoted(dir.path()) + " --out " + quoted(dir / out);
}

TEST(ExportCommand, EveryFormatFromAnAlignFolder) {
  TempDir dir;
  make_dataset(dir, false);
  const auto points = run_floorgrid(export_args(dir, "qgis-points", "plan.points"));
  ASSERT_EQ(points.status, 0) << points.err;
  EXPECT_NE(points.out.find("63 control points"), std::string::npos) << points.out;
  EXPECT_NE(points.out.find("plan raster pixels"), std::string::npos) << points.out;
  EXPECT_EQ(read_file(dir / "plan.points").rfind("#CRS: \nmapX,mapY,sourceX,sourceY", 0), 0u);

  const auto vrt = run_floorgrid(export_args(dir, "gdal-vrt", "plan.vrt"));
  ASSERT_EQ(vrt.status, 0) << vrt.err;
  EXPECT_NE(vrt.out.find("gdalwarp -order 1"), std::string::npos) << vrt.out;

  const auto rmf = run_floorgrid(export_args(dir, "rmf", "rmf.yaml"));
  ASSERT_EQ(rmf.status, 0) << rmf.err;
  EXPECT_NE(read_file(dir / "rmf.yaml").find("filename: \"gridmap.pgm\""), std::string::npos);
  // Both maps are 0.05 m and the truth is rigid: scale 0.05, yaw -0.25 (level y is down).
  EXPECT_NE(rmf.out.find("scale 0.05 m/pixel"), std::string::npos) << rmf.out;
  EXPECT_NE(rmf.out.find("yaw -0.250000 rad"), std::string::npos) << rmf.out;

  const auto nav2 = run_floorgrid(export_args(dir, "nav2-map", "walls.yaml"));
  ASSERT_EQ(nav2.status, 0) << nav2.err;
  const io::LoadedMap walls = io::read_map_yaml(dir / "walls.yaml");
  const io::LoadedMap grid = io::read_map_yaml(dir / "gridmap.yaml");
  EXPECT_EQ(walls.grid.width(), grid.grid.width());
  EXPECT_EQ(walls.grid.height(), grid.grid.height());
  EXPECT_DOUBLE_EQ(walls.metadata.origin.x, grid.metadata.origin.x);
  // The plan's walls through the exact truth land on the gridmap's walls.
  std::size_t on_walls = 0, total = 0;
  for (int iy = 0; iy < walls.grid.height(); ++iy) {
    for (int ix = 0; ix < walls.grid.width(); ++ix) {
      if (walls.grid.state(ix, iy) != CellState::occupied)
        continue;
      ++total;
      bool near = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          near = near || grid.grid.is_occupied(ix + dx, iy + dy);
      on_walls += near;
    }
  }
  EXPECT_GT(total, 500u);
  EXPECT_GT(double(on_walls), 0.99 * double(total));
}

TEST(ExportCommand, VrtAgreesWithFloorgridMapThroughGdaltransform) {
  if (!test::have_program("gdaltransform"))
    GTEST_SKIP() << "gdaltransform (Debian gdal-bin) not installed";
  TempDir dir;
  make_dataset(dir, false);
  ASSERT_EQ(run_floorgrid(export_args(dir, "gdal-vrt", "plan.vrt")).status, 0);
  const io::LoadedMap plan = io::read_map_yaml(dir / "plan.yaml");
  const GridGeometry& g = plan.grid.geometry();
  for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(10.5, 20.25), Eigen::Vector2d(200, 3)}) {
    write_file(dir / "in.txt", fmt::format("{} {}\n", pixel.x(), pixel.y()));
    const auto gdal = test::run_command("gdaltransform -order 1 " + quoted(dir / "plan.vrt") +
                                        " < " + quoted(dir / "in.txt"));
    ASSERT_EQ(gdal.status, 0) << gdal.err;
    double gx = 0, gy = 0;
    std::istringstream(gdal.out) >> gx >> gy;
    // The same point through `floorgrid map`: the pixel in plan metres, by the map YAML.
    const Eigen::Vector2d p = g.from_cell_coordinates({pixel.x(), g.height - pixel.y()});
    const auto map = run_floorgrid("map --model " + quoted(dir / "al" / "model.json") + " " +
                                   fmt::format("{},{}", p.x(), p.y()));
    ASSERT_EQ(map.status, 0) << map.err;
    double mx = 0, my = 0;
    ASSERT_EQ(std::sscanf(map.out.c_str(), "%*s -> %lf,%lf", &mx, &my), 2) << map.out;
    EXPECT_LT(std::hypot(gx - mx, gy - my), 1e-3) << gdal.out << map.out;
  }
}

TEST(ExportCommand, DxfPlan) {
  TempDir dir;
  make_dataset(dir, true);
  const auto vrt = run_floorgrid(export_args(dir, "gdal-vrt", "plan.vrt"));
  EXPECT_EQ(vrt.status, 2);
  EXPECT_NE(vrt.err.find("--source"), std::string::npos) << vrt.err;
  EXPECT_NE(vrt.err.find("DXF"), std::string::npos) << vrt.err;
  EXPECT_FALSE(fs::exists(dir / "plan.vrt"));
  const auto grid_vrt =
      run_floorgrid(export_args(dir, "gdal-vrt", "gridmap.vrt") + " --source gridmap");
  EXPECT_EQ(grid_vrt.status, 0) << grid_vrt.err;
  const auto points = run_floorgrid(export_args(dir, "qgis-points", "plan.points"));
  EXPECT_EQ(points.status, 0) << points.err;
  EXPECT_NE(points.out.find("plan metres"), std::string::npos) << points.out;
  EXPECT_EQ(run_floorgrid(export_args(dir, "nav2-map", "walls.yaml")).status, 0);
  const auto rmf = run_floorgrid(export_args(dir, "rmf", "rmf.yaml"));
  EXPECT_EQ(rmf.status, 0) << rmf.err;
  EXPECT_NE(rmf.out.find("y flipped"), std::string::npos) << rmf.out;
}

TEST(ExportCommand, BadInputIsExitTwoNamingWhatIsMissing) {
  TempDir dir;
  make_dataset(dir, false);
  const std::string model = " --model " + quoted(dir / "al" / "model.json");
  for (const char* format : {"gdal-vrt", "rmf", "nav2-map"}) {
    const auto r =
        run_floorgrid("export" + model + " --format " + format + " --out " + quoted(dir / "x.out"));
    EXPECT_EQ(r.status, 2) << format;
    EXPECT_NE(r.err.find("--dataset"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.out"));
  }
  // A model without pairs.csv beside it, and no --pairs.
  fs::copy_file(dir / "al" / "model.json", dir / "lone.json");
  const auto lone = run_floorgrid("export --model " + quoted(dir / "lone.json") +
                                  " --format qgis-points --out " + quoted(dir / "x.points"));
  EXPECT_EQ(lone.status, 2);
  EXPECT_NE(lone.err.find("--pairs"), std::string::npos) << lone.err;
  const auto bad_format =
      run_floorgrid("export" + model + " --format kml --out " + quoted(dir / "x.kml"));
  EXPECT_EQ(bad_format.status, 2);
  const auto no_model =
      run_floorgrid("export --model " + quoted(dir / "none.json") + " --format rmf --dataset " +
                    quoted(dir.path()) + " --out " + quoted(dir / "x.yaml"));
  EXPECT_EQ(no_model.status, 2);
  EXPECT_NE(no_model.err.find("none.json"), std::string::npos) << no_model.err;
  const auto bad_pairs =
      run_floorgrid("export" + model + " --format qgis-points --pairs " +
                    quoted(dir / "missing.csv") + " --out " + quoted(dir / "x.points"));
  EXPECT_EQ(bad_pairs.status, 2);
  EXPECT_NE(bad_pairs.err.find("missing.csv"), std::string::npos) << bad_pairs.err;
}

}  // namespace
}  // namespace floorgrid
