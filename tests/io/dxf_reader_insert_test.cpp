// DXF reader: block references. Expected coordinates are worked out by hand from the DXF
// reference's INSERT transform (OCS(insert + R(rotation) S (p - base))); the harder compositions
// are compared with ezdxf's own Insert.virtual_entities() and multi_insert().

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;

/// Block B: base (1,1); a LINE (1,1)-(3,1) and an ARC centre (1,1) radius 1 from 0 to 90 degrees,
/// both on layer 0, and a LINE (1,1)-(1,2) on its own layer OWN.
const char* const kBlockB = R"(0 BLOCK
8 0
2 B
70 0
10 1
20 1
30 0
0 LINE
8 0
10 1
20 1
11 3
21 1
0 ARC
8 0
10 1
20 1
40 1
50 0
51 90
0 LINE
8 OWN
10 1
20 1
11 1
21 2
0 ENDBLK
8 0)";

void expect_point(const Eigen::Vector2d& actual, double x, double y, double tol = kTol) {
  EXPECT_NEAR(actual.x(), x, tol);
  EXPECT_NEAR(actual.y(), y, tol);
}

/// The segment and arc made from block B's layer-0 entities.
struct Placed {
  Segment line;
  Arc arc;
};

Placed only_placement(const VectorFloorplan& plan) {
  EXPECT_EQ(plan.segments().size(), 2u);
  EXPECT_EQ(plan.arcs().size(), 1u);
  Placed placed;
  if (!plan.segments().empty()) {
    placed.line = plan.segments()[0];
  }
  if (!plan.arcs().empty()) {
    placed.arc = plan.arcs()[0];
  }
  return placed;
}

TEST(DxfReaderInsert, RotatedScaledInsertHonoursBasePointAndInheritsLayer) {
  TempDir dir;
  const auto path = put(dir, dxf_file(R"(0 INSERT
8 WALLS
2 B
10 10
20 20
41 2
42 2
50 90)",
                                      kBlockB));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const Placed p = only_placement(read.plan);
  // (1,1) is the base: it lands on the insertion point; (3,1) is 2 along x, scaled to 4, turned
  // to +y.
  expect_point(p.line.a, 10.0, 20.0);
  expect_point(p.line.b, 10.0, 24.0);
  EXPECT_EQ(read.plan.layers()[p.line.layer], "WALLS");
  expect_point(p.arc.center, 10.0, 20.0);
  EXPECT_NEAR(p.arc.radius, 2.0, kTol);
  // The arc's 0-degree end, block (2,1), is 1 along x from the base: 2 after scaling, turned to
  // +y; its 90-degree end turns to -x.
  expect_point(p.arc.point_at(p.arc.start_angle), 10.0, 22.0);
  expect_point(p.arc.point_at(p.arc.end_angle), 8.0, 20.0);
  const std::map<std::string, std::map<std::string, std::size_t>> layers = {
      {"WALLS", {{"LINE", 1}, {"ARC", 1}}}, {"OWN", {{"LINE", 1}}}};
  EXPECT_EQ(read.report.entities_by_layer, layers);
  EXPECT_EQ(read.report.inserts_expanded, 1u);
}

TEST(DxfReaderInsert, NegativeScaleMirrorsAndFlipsArcSweep) {
  TempDir dir;
  // x scale -1 mirrors in x: block (p - base) = (dx, dy) goes to (-dx, dy).
  const auto path = put(dir, dxf_file("0 INSERT\n8 M\n2 B\n10 0\n20 0\n41 -1\n42 1", kBlockB));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const Placed p = only_placement(read.plan);
  expect_point(p.line.b, -2.0, 0.0);
  // The quarter arc from 0 to 90 degrees becomes the quarter from 90 to 180 degrees.
  expect_point(p.arc.center, 0.0, 0.0);
  EXPECT_NEAR(p.arc.end_angle - p.arc.start_angle, kPi / 2, kTol);
  expect_point(p.arc.point_at(p.arc.start_angle), 0.0, 1.0);
  expect_point(p.arc.point_at(p.arc.end_angle), -1.0, 0.0);
}

TEST(DxfReaderInsert, NegativeUniformScaleIsAHalfTurn) {
  TempDir dir;
  const auto path = put(dir, dxf_file("0 INSERT\n8 M\n2 B\n10 5\n20 5\n41 -2\n42 -2", kBlockB));
  const Placed p = only_placement(io::read_dxf(path, metres()).plan);
  expect_point(p.line.b, 1.0, 5.0);
  EXPECT_NEAR(p.arc.radius, 2.0, kTol);
  expect_point(p.arc.point_at(p.arc.start_angle), 3.0, 5.0);  // 0 deg -> 180 deg, still CCW
  expect_point(p.arc.point_at(p.arc.end_angle), 5.0, 3.0);
}

TEST(DxfReaderInsert, ExtrusionMinusZPlacesInTheMirroredOcs) {
  TempDir dir;
  // OCS of (0,0,-1): OCS (x, y) is world (-x, y). The insertion point (5, 0) is in that OCS.
  const auto path =
      put(dir, dxf_file("0 INSERT\n8 M\n2 B\n10 5\n20 0\n210 0\n220 0\n230 -1", kBlockB));
  const Placed p = only_placement(io::read_dxf(path, metres()).plan);
  expect_point(p.line.a, -5.0, 0.0);
  expect_point(p.line.b, -7.0, 0.0);
  expect_point(p.arc.center, -5.0, 0.0);
  expect_point(p.arc.point_at(p.arc.start_angle), -5.0, 1.0);
  expect_point(p.arc.point_at(p.arc.end_angle), -6.0, 0.0);
}

TEST(DxfReaderInsert, NonUniformScaleTurnsArcsIntoSegmentsOnTheEllipse) {
  TempDir dir;
  const auto path = put(dir, dxf_file("0 INSERT\n8 N\n2 B\n10 0\n20 0\n41 3\n42 1", kBlockB));
  io::DxfReadOptions options = metres();
  options.curve_tolerance = 0.001;
  const io::DxfFloorplan read = io::read_dxf(path, options);
  EXPECT_TRUE(read.plan.arcs().empty());
  // The quarter circle becomes x = 3 cos t, y = sin t, t in [0, 90 deg], from (3,0) to (0,1).
  std::size_t on_ellipse = 0;
  for (const Segment& s : read.plan.segments()) {
    if (s.a.y() == 0.0 && s.b.y() == 0.0) {
      continue;  // the block's LINE, now (0,0)-(6,0)
    }
    if (s.a.x() == 0.0 && s.b.x() == 0.0) {
      continue;  // the OWN line, (0,0)-(0,1)
    }
    for (const Eigen::Vector2d& q : {s.a, s.b}) {
      EXPECT_NEAR(std::pow(q.x() / 3.0, 2) + q.y() * q.y(), 1.0, 1e-12);
    }
    ++on_ellipse;
  }
  EXPECT_GE(on_ellipse, 8u);
  EXPECT_EQ(read.report.entities_by_type.at("ARC"), 1u);  // still counted as the ARC it was
}

TEST(DxfReaderInsert, MinsertGridIsRotatedButNotScaled) {
  TempDir dir;
  // 3 columns x 2 rows, spacing 10 (columns) and 20 (rows), rotated 90 degrees, scale 2: cell
  // (c, r) is offset R(90)(10c, 20r) = (-20r, 10c) from the insertion point (5,5).
  const auto path = put(dir, dxf_file(R"(0 INSERT
8 GRID
2 B
10 5
20 5
41 2
42 2
50 90
70 3
71 2
44 10
45 20)",
                                      kBlockB));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  EXPECT_EQ(read.plan.segments().size(), 12u);
  EXPECT_EQ(read.plan.arcs().size(), 6u);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d origin(5.0 - 20.0 * r, 5.0 + 10.0 * c);
      bool found = false;
      for (const Segment& s : read.plan.segments()) {
        found |= (s.a - origin).norm() < 1e-12 &&
                 (s.b - (origin + Eigen::Vector2d(0, 4))).norm() < 1e-12;
      }
      EXPECT_TRUE(found) << "cell " << c << ", " << r;
    }
  }
  EXPECT_EQ(read.report.entities_by_type.at("LINE"), 12u);
  EXPECT_EQ(read.report.inserts_expanded, 1u);
}

TEST(DxfReaderInsert, NestedBlocksInheritLayerZeroFromTheNearestNamedInsert) {
  TempDir dir;
  // A holds B twice: on layer 0 at (1,0) turned 90 degrees, and on layer MID at (0,5). A is
  // placed on OUTER at (10,0) with scale 2.
  const std::string blocks = std::string(kBlockB) + "\n" + R"(0 BLOCK
8 0
2 A
70 0
10 0
20 0
0 INSERT
8 0
2 B
10 1
20 0
50 90
0 INSERT
8 MID
2 B
10 0
20 5
0 ENDBLK)";
  const auto path = put(dir, dxf_file("0 INSERT\n8 OUTER\n2 A\n10 10\n20 0\n41 2\n42 2", blocks));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  const VectorFloorplan& plan = read.plan;
  const auto find_line = [&](const std::string& layer, const Eigen::Vector2d& a,
                             const Eigen::Vector2d& b) {
    for (const Segment& s : plan.segments()) {
      if (plan.layers()[s.layer] == layer && (s.a - a).norm() < 1e-12 && (s.b - b).norm() < 1e-12) {
        return true;
      }
    }
    return false;
  };
  // Via the layer-0 INSERT: B's line (1,1)-(3,1) is (0,0)-(2,0) from B's base, turned to
  // (0,0)-(0,2), moved to (1,0)-(1,2) in A, then doubled and moved: (12,0)-(12,4) on OUTER.
  EXPECT_TRUE(find_line("OUTER", {12, 0}, {12, 4}));
  // Via the MID INSERT: (0,5)-(2,5) in A, world (10,10)-(14,10), on MID, not OUTER.
  EXPECT_TRUE(find_line("MID", {10, 10}, {14, 10}));
  // B's own-layer line keeps its layer in both placements.
  EXPECT_TRUE(find_line("OWN", {12, 0}, {10, 0}));
  EXPECT_TRUE(find_line("OWN", {10, 10}, {10, 12}));
  const std::map<std::string, std::map<std::string, std::size_t>> layers = {
      {"OUTER", {{"LINE", 1}, {"ARC", 1}}},
      {"MID", {{"LINE", 1}, {"ARC", 1}}},
      {"OWN", {{"LINE", 2}}}};
  EXPECT_EQ(read.report.entities_by_layer, layers);
  EXPECT_EQ(read.report.inserts_expanded, 3u);
}

TEST(DxfReaderInsert, ComplexCompositionMatchesEzdxf) {
  FLOORGRID_REQUIRE_EZDXF();
  TempDir dir;
  // Three levels: C (an LWPOLYLINE with a bulge in a mirrored OCS, a CIRCLE, a SOLID) inside A
  // rotated, mirrored and non-uniformly scaled, inside a MINSERT grid with extrusion (0,0,-1).
  const std::string blocks = R"(0 BLOCK
8 0
2 C
70 0
10 0.5
20 -0.25
0 LWPOLYLINE
100 AcDbEntity
8 0
100 AcDbPolyline
90 3
70 0
10 0
20 0
42 0.4142135623730951
10 1
20 0
10 1
20 2
210 0
220 0
230 -1
0 CIRCLE
8 RING
10 2
20 1
40 0.5
0 SOLID
8 0
10 0
20 0
11 1
21 0
12 0
22 1
13 1
23 1
0 ARC
8 0
10 0
20 0
40 3
50 30
51 300
0 ENDBLK
0 BLOCK
8 0
2 A
70 0
10 1
20 2
0 INSERT
8 0
2 C
10 3
20 -1
41 -1.5
42 1.5
50 37
0 INSERT
8 INNER
2 C
10 -4
20 2
41 2
42 0.5
50 -20
0 ENDBLK)";
  const auto path = put(dir, dxf_file(R"(0 INSERT
8 TOP
2 A
10 2
20 3
41 1.25
42 1.25
50 15
70 2
71 3
44 7
45 -9
210 0
220 0
230 -1)",
                                      blocks, "9 $ACADVER\n1 AC1015"));
  io::DxfReadOptions options = metres();
  options.curve_tolerance = 0.001;
  const io::DxfFloorplan read = io::read_dxf(path, options);
  expect_same_geometry(read.plan, ezdxf_dump(path, true, 1e-5), 1.0, 1e-9, 0.001 + 1e-5);
  // Counts by hand: 6 grid cells, each placing C twice (once on layer 0 -> TOP, once on INNER);
  // ezdxf cannot tell them, as it re-types non-uniformly scaled curves (ARC -> ELLIPSE).
  const std::map<std::string, std::map<std::string, std::size_t>> layers = {
      {"TOP", {{"ARC", 6}, {"LWPOLYLINE", 6}, {"SOLID", 6}}},
      {"INNER", {{"ARC", 6}, {"LWPOLYLINE", 6}, {"SOLID", 6}}},
      {"RING", {{"CIRCLE", 12}}}};
  EXPECT_EQ(read.report.entities_by_layer, layers);
  // The mirror-similar placement keeps true arcs: the ARC, the bulge and the CIRCLE, per cell.
  EXPECT_EQ(read.plan.arcs().size(), 6u * 3u);
  // The grid INSERT once, then A's two INSERTs in each of the 6 cells.
  EXPECT_EQ(read.report.inserts_expanded, 1u + 6u * 2u);
}

TEST(DxfReaderInsert, SelfReferenceAndMissingBlocksAreWarningsNotHangs) {
  TempDir dir;
  const std::string blocks = R"(0 BLOCK
2 LOOP
10 0
20 0
0 LINE
8 L
10 0
20 0
11 1
21 0
0 INSERT
2 LOOP
10 1
20 0
0 ENDBLK)";
  const auto path =
      put(dir,
          dxf_file("0 INSERT\n8 X\n2 LOOP\n10 0\n20 0\n0 INSERT\n8 X\n2 NOPE\n10 0\n20 0", blocks));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  EXPECT_EQ(read.plan.segments().size(), 1u);
  const auto warned = [&](const std::string& text) {
    return std::any_of(read.report.warnings.begin(), read.report.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != w.npos; });
  };
  EXPECT_TRUE(warned("inside itself"));
  EXPECT_TRUE(warned("\"NOPE\", which is not defined"));
}

TEST(DxfReaderInsert, HugeArraysAreRefusedByTheEntityBudget) {
  TempDir dir;
  const std::string text =
      dxf_file("0 INSERT\n8 G\n2 B\n10 0\n20 0\n70 30000\n71 30000\n44 1\n45 1", kBlockB);
  const auto path = put(dir, text);
  io::DxfReadOptions options = metres();
  options.max_entities = 100000;
  try {
    io::read_dxf(path, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "max_entities");
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.line(), line_of(text, "INSERT"));
  }
}

}  // namespace
}  // namespace floorgrid::test
