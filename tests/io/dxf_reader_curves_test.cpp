// DXF reader: ELLIPSE and SPLINE become segments. Truth: the curves' own equations, evaluated
// here, and ezdxf's flattening of the same entities.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

void expect_point(const Eigen::Vector2d& actual, double x, double y, double tol = 1e-12) {
  EXPECT_NEAR(actual.x(), x, tol);
  EXPECT_NEAR(actual.y(), y, tol);
}

TEST(DxfReaderCurves, EllipseBecomesSegmentsOnTheEllipseWithinTolerance) {
  TempDir dir;
  // Centre (1,2), major axis (3,0), ratio 0.5: x = 1 + 3 cos t, y = 2 + 1.5 sin t, t in [0, pi].
  const auto path = put(dir, dxf_file(R"(0 ELLIPSE
8 E
10 1
20 2
30 0
11 3
21 0
31 0
40 0.5
41 0
42 3.141592653589793)"));
  io::DxfReadOptions options = metres();
  options.curve_tolerance = 0.001;
  const io::DxfFloorplan read = io::read_dxf(path, options);
  const VectorFloorplan& plan = read.plan;
  ASSERT_GE(plan.segments().size(), 8u);
  EXPECT_TRUE(plan.arcs().empty());
  expect_point(plan.segments().front().a, 4.0, 2.0);
  expect_point(plan.segments().back().b, -2.0, 2.0, 1e-12);
  for (const Segment& s : plan.segments()) {
    for (const Eigen::Vector2d& p : {s.a, s.b}) {  // vertices lie on the ellipse, upper half
      EXPECT_NEAR(std::pow((p.x() - 1.0) / 3.0, 2) + std::pow((p.y() - 2.0) / 1.5, 2), 1.0, 1e-12);
      EXPECT_GE(p.y(), 2.0 - 1e-12);
    }
    // The chord's midpoint is at most the tolerance inside the curve (radial check is an upper
    // bound on the distance for this convex curve).
    const Eigen::Vector2d m = 0.5 * (s.a + s.b);
    const double t = std::atan2((m.y() - 2.0) / 1.5, (m.x() - 1.0) / 3.0);
    const Eigen::Vector2d on(1.0 + 3.0 * std::cos(t), 2.0 + 1.5 * std::sin(t));
    EXPECT_LE((on - m).norm(), 0.001 + 1e-12);
  }
}

TEST(DxfReaderCurves, SplineIsEvaluatedFromControlPointsAndKnots) {
  TempDir dir;
  // A clamped cubic with 4 control points is the Bezier curve of those points.
  const auto path = put(dir, dxf_file(R"(0 SPLINE
8 SP
70 8
71 3
72 8
73 4
40 0
40 0
40 0
40 0
40 1
40 1
40 1
40 1
10 0
20 0
30 0
10 1
20 2
30 0
10 3
20 2
30 0
10 4
20 0
30 0)"));
  io::DxfReadOptions options = metres();
  options.curve_tolerance = 0.0005;
  const io::DxfFloorplan read = io::read_dxf(path, options);
  const VectorFloorplan& plan = read.plan;
  ASSERT_GE(plan.segments().size(), 4u);
  const auto bezier = [](double t) {
    const double u = 1.0 - t;
    return Eigen::Vector2d(3 * u * u * t * 1 + 3 * u * t * t * 3 + t * t * t * 4,
                           3 * u * u * t * 2 + 3 * u * t * t * 2);
  };
  expect_point(plan.segments().front().a, 0.0, 0.0);
  expect_point(plan.segments().back().b, 4.0, 0.0);
  for (const Segment& s : plan.segments()) {
    // x(t) increases with t here: find t for the vertex's x by bisection and compare y.
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (bezier(mid).x() < s.b.x() ? lo : hi) = mid;
    }
    EXPECT_NEAR(s.b.y(), bezier(lo).y(), 1e-9);
  }
  EXPECT_EQ(read.report.entities_by_type.at("SPLINE"), 1u);
}

TEST(DxfReaderCurves, RationalSplineQuarterCircleStaysOnTheCircle) {
  TempDir dir;
  const auto path = put(dir, dxf_file(R"(0 SPLINE
8 SP
70 12
71 2
72 6
73 3
40 0
40 0
40 0
40 1
40 1
40 1
41 1
41 0.70710678118654757
41 1
10 1
20 0
30 0
10 1
20 1
30 0
10 0
20 1
30 0)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_GE(read.plan.segments().size(), 2u);
  for (const Segment& s : read.plan.segments()) {
    EXPECT_NEAR(s.b.norm(), 1.0, 1e-12);
  }
  expect_point(read.plan.segments().back().b, 0.0, 1.0);
}

TEST(DxfReaderCurves, CurvesMatchEzdxfFlattening) {
  FLOORGRID_REQUIRE_EZDXF();
  TempDir dir;
  // An ELLIPSE tilted out of the XY plane (extrusion (0,1,1)), an unclamped cubic SPLINE and a
  // CIRCLE in a tilted OCS, which projects to an ellipse.
  const auto path = put(dir, dxf_file(R"(0 ELLIPSE
100 AcDbEntity
8 C
100 AcDbEllipse
10 1
20 2
30 0
11 2
21 0
31 0
210 0
220 0.70710678118654757
230 0.70710678118654757
40 0.4
41 0.5
42 5
0 SPLINE
100 AcDbEntity
8 C
100 AcDbSpline
70 8
71 3
72 10
73 6
40 0
40 1
40 2
40 3
40 4
40 5
40 6
40 7
40 8
40 9
10 0
20 0
30 0
10 1
20 3
30 0
10 3
20 -1
30 0
10 5
20 4
30 0
10 6
20 0
30 0
10 8
20 2
30 0
0 CIRCLE
8 C
10 3
20 -2
30 1
40 1.5
210 0.6
220 0
230 0.8)",
                                      {}, "9 $ACADVER\n1 AC1015"));
  io::DxfReadOptions options = metres();
  options.curve_tolerance = 0.001;
  const io::DxfFloorplan read = io::read_dxf(path, options);
  const nlohmann::json dump = ezdxf_dump(path, true, 1e-5);
  expect_same_counts(read.report, dump);
  // ezdxf's points lie within our chord tolerance of our segments.
  expect_same_geometry(read.plan, dump, 1.0, 1e-9, 0.001 + 1e-5);
}

TEST(DxfReaderCurves, SplineWithFitPointsOnlyIsDrawnThroughThem) {
  TempDir dir;
  const auto path = put(dir, dxf_file(R"(0 SPLINE
8 SP
70 8
71 3
74 3
11 0
21 0
31 0
11 1
21 1
31 0
11 2
21 0
31 0)"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.segments().size(), 2u);
  expect_point(read.plan.segments()[0].b, 1.0, 1.0);
  EXPECT_TRUE(std::any_of(read.report.warnings.begin(), read.report.warnings.end(),
                          [](const std::string& w) { return w.find("fit points") != w.npos; }));
}

}  // namespace
}  // namespace floorgrid::test
