// DXF reader: one entity type at a time, each DXF hand-written and its geometry computed here by
// hand; curves are also compared with ezdxf's own flattening.

#include "floorgrid/io/plans/dxf_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;

void expect_point(const Eigen::Vector2d& actual, double x, double y, double tol = kTol) {
  EXPECT_NEAR(actual.x(), x, tol);
  EXPECT_NEAR(actual.y(), y, tol);
}

/// Whether the plan has a segment between the two points (either direction).
bool has_segment(const VectorFloorplan& plan, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  for (const Segment& s : plan.segments()) {
    if (((s.a - a).norm() < 1e-9 && (s.b - b).norm() < 1e-9) ||
        ((s.a - b).norm() < 1e-9 && (s.b - a).norm() < 1e-9)) {
      return true;
    }
  }
  return false;
}

TEST(DxfReader, ReadsLineWithFullDoublePrecision) {
  TempDir dir;
  // libdime stores coordinates as float and would return 123456.7890625 here.
  const auto path = put(dir, dxf_file(R"(0 LINE
8 WALLS
10 1.23456789012345
20 123456.789012345
30 0
11 -7.5
21 0.1
31 0)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.segments().size(), 1u);
  const Segment& s = read.plan.segments()[0];
  EXPECT_EQ(s.a.x(), 1.23456789012345);
  EXPECT_EQ(s.a.y(), 123456.789012345);
  EXPECT_EQ(s.b.x(), -7.5);
  EXPECT_EQ(s.b.y(), 0.1);
  EXPECT_EQ(read.plan.layers()[s.layer], "WALLS");
  EXPECT_EQ(read.report.entities_by_type.at("LINE"), 1u);
  EXPECT_EQ(read.report.entities_by_layer.at("WALLS").at("LINE"), 1u);
}

TEST(DxfReader, LwpolylineBulgesBecomeArcsAndClosedFlagClosesIt) {
  TempDir dir;
  // (0,0) -bulge 1-> (2,0) -> (2,2) -bulge -0.5-> (0,2) -> closing line to (0,0).
  const auto path = put(dir, dxf_file(R"(0 LWPOLYLINE
100 AcDbEntity
8 P
100 AcDbPolyline
90 4
70 1
10 0
20 0
42 1
10 2
20 0
10 2
20 2
42 -0.5
10 0
20 2)",
                                      {}, "9 $ACADVER\n1 AC1015"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const VectorFloorplan& plan = read.plan;
  ASSERT_EQ(plan.arcs().size(), 2u);
  ASSERT_EQ(plan.segments().size(), 2u);
  EXPECT_TRUE(has_segment(plan, {2, 0}, {2, 2}));
  EXPECT_TRUE(has_segment(plan, {0, 2}, {0, 0}));
  // Bulge 1 is a half circle turning counter-clockwise from (0,0) to (2,0): it bulges below.
  const Arc& half = plan.arcs()[0];
  expect_point(half.center, 1.0, 0.0);
  EXPECT_NEAR(half.radius, 1.0, kTol);
  EXPECT_NEAR(half.end_angle - half.start_angle, kPi, kTol);
  expect_point(half.point_at(0.5 * (half.start_angle + half.end_angle)), 1.0, -1.0);
  // Bulge -0.5 from (2,2) to (0,2), clockwise: moving in -x while turning clockwise is the
  // bottom of a circle, so the arc sags below the chord by the sagitta 0.5 * half-chord 1.
  const Arc& cw = plan.arcs()[1];
  const double included = 4.0 * std::atan(0.5);
  EXPECT_NEAR(cw.end_angle - cw.start_angle, included, kTol);
  EXPECT_NEAR(cw.radius, 1.0 / std::sin(included / 2.0), kTol);
  expect_point(cw.point_at(0.5 * (cw.start_angle + cw.end_angle)), 1.0, 1.5);
  const Eigen::Vector2d p = cw.point_at(cw.start_angle), q = cw.point_at(cw.end_angle);
  EXPECT_TRUE(
      ((p - Eigen::Vector2d(0, 2)).norm() < 1e-12 && (q - Eigen::Vector2d(2, 2)).norm() < 1e-12));
  EXPECT_EQ(read.report.entities_by_type.at("LWPOLYLINE"), 1u);
  if (ezdxf_available()) {  // ezdxf splits the polyline into the same lines and arcs
    expect_same_geometry(plan, ezdxf_dump(path, true), 1.0, 1e-12);
  }
}

TEST(DxfReader, ClosedTwoVertexPolylineWithBulgesIsAFullCircle) {
  TempDir dir;
  // AutoCAD's DONUT: two vertices, bulge 1 each, closed: two half circles around (1,0).
  const auto path = put(dir, dxf_file(R"(0 LWPOLYLINE
8 D
90 2
70 1
10 0
20 0
42 1
10 2
20 0
42 1)"));
  const VectorFloorplan plan = io::read_dxf(path, metres()).plan;
  ASSERT_EQ(plan.arcs().size(), 2u);
  EXPECT_TRUE(plan.segments().empty());
  double sweep = 0.0;
  for (const Arc& arc : plan.arcs()) {
    expect_point(arc.center, 1.0, 0.0);
    EXPECT_NEAR(arc.radius, 1.0, kTol);
    sweep += arc.end_angle - arc.start_angle;
  }
  EXPECT_NEAR(sweep, 2.0 * kPi, kTol);
  // One half passes below the chord, the other above.
  const Arc& a = plan.arcs()[0];
  const Arc& b = plan.arcs()[1];
  EXPECT_NEAR(a.point_at(0.5 * (a.start_angle + a.end_angle)).y() +
                  b.point_at(0.5 * (b.start_angle + b.end_angle)).y(),
              0.0, kTol);
}

TEST(DxfReader, OldStylePolylineWithVertexBulgesAnd3dPolylineAndMeshSkipped) {
  TempDir dir;
  const auto path = put(dir, dxf_file(R"(0 POLYLINE
8 OLD
66 1
10 0
20 0
30 5
70 1
0 VERTEX
8 OLD
10 0
20 0
30 5
42 1
0 VERTEX
8 OLD
10 4
20 0
30 5
0 VERTEX
8 OLD
10 4
20 3
30 5
0 SEQEND
0 POLYLINE
8 OLD3D
66 1
10 0
20 0
30 0
70 8
0 VERTEX
10 1
20 1
30 7
70 32
0 VERTEX
10 2
20 3
30 -4
70 32
0 SEQEND
0 POLYLINE
8 MESH
66 1
70 64
0 VERTEX
10 0
20 0
30 0
0 SEQEND)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const VectorFloorplan& plan = read.plan;
  // 2D: half circle (0,0)->(4,0), line (4,0)->(4,3), closing line (4,3)->(0,0).
  ASSERT_EQ(plan.arcs().size(), 1u);
  expect_point(plan.arcs()[0].center, 2.0, 0.0);
  EXPECT_NEAR(plan.arcs()[0].radius, 2.0, kTol);
  EXPECT_TRUE(has_segment(plan, {4, 0}, {4, 3}));
  EXPECT_TRUE(has_segment(plan, {4, 3}, {0, 0}));
  // 3D polyline: world vertices projected onto XY.
  EXPECT_TRUE(has_segment(plan, {1, 1}, {2, 3}));
  EXPECT_EQ(plan.segments().size(), 3u);
  EXPECT_EQ(read.report.entities_by_type.at("POLYLINE"), 2u);
  EXPECT_EQ(read.report.unsupported_skipped.at("POLYLINE (mesh)"), 1u);
}

TEST(DxfReader, ArcAndCircleStayCircularAndFullCircleSpansTwoPi) {
  TempDir dir;
  const auto path = put(dir, dxf_file(R"(0 ARC
8 DOORS
10 1
20 2
30 0
40 0.9
50 350
51 80
0 CIRCLE
8 COLUMNS
10 -3
20 4
30 0
40 0.25)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.arcs().size(), 2u);
  const Arc& door = read.plan.arcs()[0];
  expect_point(door.center, 1.0, 2.0);
  EXPECT_NEAR(door.radius, 0.9, kTol);
  EXPECT_NEAR(door.end_angle - door.start_angle, 90.0 * kPi / 180.0, kTol);  // across 0 degrees
  expect_point(door.point_at(door.start_angle), 1.0 + 0.9 * std::cos(-10.0 * kPi / 180.0),
               2.0 + 0.9 * std::sin(-10.0 * kPi / 180.0));
  const Arc& column = read.plan.arcs()[1];
  expect_point(column.center, -3.0, 4.0);
  EXPECT_NEAR(column.end_angle - column.start_angle, 2.0 * kPi, kTol);
  EXPECT_EQ(read.report.entities_by_layer.at("DOORS").at("ARC"), 1u);
  EXPECT_EQ(read.report.entities_by_layer.at("COLUMNS").at("CIRCLE"), 1u);
}

TEST(DxfReader, NegativeZExtrusionMirrorsArcsCirclesAndPolylinesThroughTheOcs) {
  TempDir dir;
  // OCS of extrusion (0,0,-1) by the arbitrary axis algorithm: x_ocs = (-1,0,0), y_ocs = (0,1,0),
  // so OCS (x, y) is world (-x, y), and counter-clockwise in the OCS is clockwise in the world.
  const auto path = put(dir, dxf_file(R"(0 ARC
8 M
10 2
20 3
30 0
40 1
50 0
51 90
210 0
220 0
230 -1
0 CIRCLE
8 M
10 5
20 1
30 0
40 2
210 0
220 0
230 -1
0 LWPOLYLINE
8 M
90 2
70 0
10 1
20 1
42 1
10 3
20 1
210 0
220 0
230 -1)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.arcs().size(), 3u);
  // ARC: centre (-2,3); OCS angles 0..90 map to world 180..90, so counter-clockwise 90..180.
  const Arc& arc = read.plan.arcs()[0];
  expect_point(arc.center, -2.0, 3.0);
  EXPECT_NEAR(arc.radius, 1.0, kTol);
  expect_point(arc.point_at(arc.start_angle), -2.0, 4.0);
  expect_point(arc.point_at(arc.end_angle), -3.0, 3.0);
  expect_point(read.plan.arcs()[1].center, -5.0, 1.0);
  // LWPOLYLINE bulge 1 from OCS (1,1) to (3,1) bulges to OCS y = 0 (below); mirrored in x only,
  // so it runs from world (-1,1) to (-3,1) with its middle at (-2,0).
  const Arc& bulge = read.plan.arcs()[2];
  expect_point(bulge.center, -2.0, 1.0);
  expect_point(bulge.point_at(0.5 * (bulge.start_angle + bulge.end_angle)), -2.0, 0.0);
}

TEST(DxfReader, SolidAndTraceOutlinesFollowTheirZOrder) {
  TempDir dir;
  // DXF stores quad corners as 1, 2, 4, 3: (0,0) (2,0) (0,1) (2,1) is the rectangle 0,0..2,1.
  const auto path = put(dir, dxf_file(R"(0 SOLID
8 S
10 0
20 0
11 2
21 0
12 0
22 1
13 2
23 1
0 TRACE
8 S
10 10
20 0
11 12
21 0
12 10
22 1
13 12
23 1
0 SOLID
8 S
10 20
20 0
11 22
21 0
12 21
22 1)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const VectorFloorplan& plan = read.plan;
  EXPECT_EQ(plan.segments().size(), 4u + 4u + 3u);  // the last SOLID is a triangle
  for (const double x : {0.0, 10.0}) {
    EXPECT_TRUE(has_segment(plan, {x, 0}, {x + 2, 0}));
    EXPECT_TRUE(has_segment(plan, {x + 2, 0}, {x + 2, 1}));
    EXPECT_TRUE(has_segment(plan, {x + 2, 1}, {x, 1}));
    EXPECT_TRUE(has_segment(plan, {x, 1}, {x, 0}));
  }
  EXPECT_TRUE(has_segment(plan, {22, 0}, {21, 1}));
  EXPECT_EQ(read.report.entities_by_type.at("SOLID"), 2u);
  EXPECT_EQ(read.report.entities_by_type.at("TRACE"), 1u);
}

TEST(DxfReader, AnnotationAndPaperSpaceAreSkippedAndCounted) {
  TempDir dir;
  std::string entities = "0 LINE\n8 W\n10 0\n20 0\n11 1\n21 0\n";
  for (const char* type : {"TEXT", "MTEXT", "DIMENSION", "LEADER", "MULTILEADER", "HATCH", "POINT",
                           "VIEWPORT", "TEXT"}) {
    entities += std::string("0 ") + type + "\n8 ANNO\n10 5\n20 5\n";
  }
  entities += "0 3DFACE\n8 W\n10 0\n20 0\n0 LINE\n8 W\n67 1\n10 0\n20 0\n11 9\n21 9\n";
  const io::DxfFloorplan read = io::read_dxf(put(dir, dxf_file(entities)), metres());
  EXPECT_EQ(read.plan.segments().size(), 1u);
  const std::map<std::string, std::size_t> expected = {
      {"TEXT", 2},        {"MTEXT", 1}, {"DIMENSION", 1}, {"LEADER", 1},
      {"MULTILEADER", 1}, {"HATCH", 1}, {"POINT", 1},     {"VIEWPORT", 1}};
  EXPECT_EQ(read.report.annotation_skipped, expected);
  EXPECT_EQ(read.report.unsupported_skipped.at("3DFACE"), 1u);
  EXPECT_EQ(read.report.paper_space_skipped, 1u);
  EXPECT_EQ(read.report.entities_by_type.at("LINE"), 1u);
}

TEST(DxfReader, LayerFiltersMatchBoundXrefLayersCaseInsensitively) {
  TempDir dir;
  std::string entities;
  for (const char* layer : {"xref-Plan$0$A-WALL", "xref-Plan$0$A-DOOR", "A-WALL", "A-FURN",
                            "xref-Plan$0$A-WALL-FURN"}) {
    entities += std::string("0 LINE\n8 ") + layer + "\n10 0\n20 0\n11 10\n21 0\n";
  }
  io::DxfReadOptions options = metres();
  options.include_layers = {"a-wall*"};
  options.exclude_layers = {"*FURN*"};
  const io::DxfFloorplan read = io::read_dxf(put(dir, dxf_file(entities)), options);
  const std::map<std::string, std::map<std::string, std::size_t>> expected = {
      {"xref-Plan$0$A-WALL", {{"LINE", 1}}}, {"A-WALL", {{"LINE", 1}}}};
  EXPECT_EQ(read.report.entities_by_layer, expected);
  EXPECT_EQ(read.report.excluded_by_layer_filter, 3u);
  EXPECT_EQ(read.plan.segments().size(), 2u);
}

TEST(DxfReader, ReportsVersionHeaderUnitsAndExtentInMetres) {
  TempDir dir;
  const auto path = put(dir, dxf_file("0 LINE\n8 W\n10 -100\n20 50\n11 1900\n21 1550", {},
                                      "9 $ACADVER\n1 AC1015\n9 $INSUNITS\n70 5"));
  const io::DxfFloorplan read = io::read_dxf(path);
  EXPECT_EQ(read.report.version, "AC1015");
  EXPECT_EQ(read.report.header_units, "cm");
  EXPECT_EQ(read.report.units_used, "cm");
  EXPECT_DOUBLE_EQ(read.report.metres_per_unit, 0.01);
  EXPECT_TRUE(read.report.warnings.empty());
  expect_point(read.report.extent_m.min(), -1.0, 0.5, 1e-12);
  expect_point(read.report.extent_m.max(), 19.0, 15.5, 1e-12);
}

}  // namespace
}  // namespace floorgrid::test
