// Zones and waypoints read from GeoJSON (plan metres), CSV and DXF layers, and what is refused:
// open and self-intersecting rings (naming the feature), WGS84 degrees, NaN, a missing DXF layer
// (listing the layers the file has).
#include "floorgrid/io/plans/plan_layers_io.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_zones.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// The InputError's full message of `f()`, or a failure.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

const char* kLayers = R"({
  "type": "FeatureCollection",
  "features": [
    {"type": "Feature", "properties": {"name": "bay", "speed_percent": 30},
     "geometry": {"type": "Polygon", "coordinates": [
       [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]],
       [[1, 1], [2, 1], [2, 2], [1, 1]]]}},
    {"type": "Feature", "properties": {"name": "dock", "theta": 1.5},
     "geometry": {"type": "Point", "coordinates": [7.5, -2.0]}},
    {"type": "Feature", "properties": {"name": "door", "heading_deg": 90},
     "geometry": {"type": "Point", "coordinates": [3.0, 4.0]}},
    {"type": "Feature", "properties": {},
     "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
    {"type": "Feature", "properties": {"name": "two rooms"},
     "geometry": {"type": "MultiPolygon", "coordinates": [
       [[[10, 0], [12, 0], [12, 2], [10, 0]]],
       [[[20, 0], [22, 0], [22, 2], [20, 0]]]]}}
  ]})";

TEST(PlanLayersIo, ReadsZonesWithHolesMultiPolygonsAndWaypointsFromGeoJson) {
  const PlanLayers layers = io::parse_plan_layers_geojson(kLayers, "layers.geojson");
  ASSERT_EQ(layers.zones.size(), 3u);
  EXPECT_EQ(layers.zones[0].name, "bay");
  EXPECT_EQ(layers.zones[0].outer.size(), 4u) << "the closing position is not repeated";
  ASSERT_EQ(layers.zones[0].holes.size(), 1u);
  EXPECT_EQ(*layers.zones[0].speed.percent, 30.0);
  EXPECT_EQ(layers.zones[1].name, "two rooms part 0");
  EXPECT_EQ(layers.zones[2].index, 4u);
  ASSERT_EQ(layers.waypoints.size(), 2u);
  EXPECT_EQ(layers.waypoints[0].name, "dock");
  EXPECT_EQ(layers.waypoints[0].position, Eigen::Vector2d(7.5, -2.0));
  EXPECT_DOUBLE_EQ(*layers.waypoints[0].theta, 1.5);
  EXPECT_DOUBLE_EQ(*layers.waypoints[1].theta, M_PI / 2);
  ASSERT_EQ(layers.warnings.size(), 1u);
  expect_contains(layers.warnings[0], "feature 3 LineString skipped");
}

TEST(PlanLayersIo, ANumberBeyondADoubleIsNotJsonNotACrash) {
  // Found by the plan_layers fuzz target: the JSON parser's out_of_range escaped as a crash.
  const std::string message = error_of([&] {
    io::parse_plan_layers_geojson(R"({"type": "Feature", "coordinates": [-61664e444, 0]})",
                                  "zones.geojson");
  });
  expect_contains(message, "zones.geojson");
  expect_contains(message, "not JSON");
}

TEST(PlanLayersIo, RefusesAnOpenRingNamingTheFeature) {
  const std::string text = R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "ok"}, "geometry": {"type": "Polygon",
     "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}},
    {"type": "Feature", "properties": {"name": "loading bay"}, "geometry": {"type": "Polygon",
     "coordinates": [[[0, 0], [4, 0], [4, 3], [0, 3]]]}}]})";
  const std::string message =
      error_of([&] { io::parse_plan_layers_geojson(text, "zones.geojson"); });
  expect_contains(message, "zones.geojson");
  expect_contains(message, "feature 1 'loading bay' outer ring: the ring is open");
}

TEST(PlanLayersIo, RefusesASelfIntersectingRingNamingTheFeatureAndTheEdges) {
  const std::string text = R"({"type": "Feature", "properties": {"name": "bow tie"},
    "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]]}})";
  const std::string message = error_of([&] { io::parse_plan_layers_geojson(text, "z.geojson"); });
  expect_contains(
      message,
      "zone 0 'bow tie': self-intersecting: outer ring edge 0 crosses outer ring edge 2 at (1, 1)");
  // A hole crossing its outer ring.
  const std::string hole = R"({"type": "Polygon", "coordinates": [
    [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]], [[3, 1], [5, 1], [5, 2], [3, 1]]]})";
  expect_contains(error_of([&] { io::parse_plan_layers_geojson(hole, "z.geojson"); }),
                  "crosses hole 0");
}

TEST(PlanLayersIo, RefusesWgs84DegreesPlanMetresOnly) {
  const std::string crs = R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}},
    "features": []})";
  const std::string by_crs = error_of([&] { io::parse_plan_layers_geojson(crs, "z.geojson"); });
  expect_contains(by_crs, "plan metres only");
  expect_contains(by_crs, "z.geojson");
  // No crs (RFC 7946 means WGS84 then): a site near Halmstad in degrees, 60 m across.
  const std::string degrees = R"({"type": "Polygon", "coordinates": [[
    [12.8761, 56.6631], [12.8771, 56.6631], [12.8771, 56.6636], [12.8761, 56.6631]]]})";
  const std::string by_extent =
      error_of([&] { io::parse_plan_layers_geojson(degrees, "z.geojson"); });
  expect_contains(by_extent, "looks like WGS84 degrees");
  expect_contains(by_extent, "plan metres only");
}

TEST(PlanLayersIo, ReadsWaypointsCsvAndRefusesNaNNamingLineAndColumn) {
  const auto waypoints =
      io::parse_waypoints_csv("name,x,y,theta\ndock,1.5,2,0.25\n# a comment\ndoor,3,4,\n", "w.csv");
  ASSERT_EQ(waypoints.size(), 2u);
  EXPECT_EQ(waypoints[1].name, "door");
  EXPECT_FALSE(waypoints[1].theta);
  EXPECT_DOUBLE_EQ(*waypoints[0].theta, 0.25);
  const std::string message =
      error_of([] { io::parse_waypoints_csv("name,x,y\ndock,1,2\nbad,nan,3\n", "w.csv"); });
  expect_contains(message, "w.csv:3");
  expect_contains(message, "'x': expected a finite number (got 'nan')");
  expect_contains(error_of([] { io::parse_waypoints_csv("x,y\n1,2\n", "w.csv"); }),
                  "expected the header name,x,y[,theta]");
  // A migrate output reads back (its further columns ignored).
  const auto again = io::parse_waypoints_csv(
      "name,x,y,theta,std_m,nearest_pair_m,flag,extrapolated\ndock,1.5,2,0.25,0.03,0.4,ok,0\n",
      "new/w.csv");
  ASSERT_EQ(again.size(), 1u);
  EXPECT_DOUBLE_EQ(*again[0].theta, 0.25);
}

class DxfZones : public ::testing::Test {
 protected:
  void SetUp() override {
    if (test::run_command("/usr/bin/python3 -c 'import ezdxf'").status != 0)
      GTEST_SKIP() << "ezdxf missing: /usr/bin/python3 -c 'import ezdxf' fails";
    const auto made = test::run_command("/usr/bin/python3 " +
                                        test::quoted(std::filesystem::path(FLOORGRID_SOURCE_DIR) /
                                                     "tests/io/make_zone_fixtures.py") +
                                        " " + test::quoted(dir_ / "zones.dxf"));
    ASSERT_EQ(made.status, 0) << made.err;
  }
  test::TempDir dir_;
};

TEST_F(DxfZones, ReadsClosedPolylinesAndHatchBoundariesOfTheLayer) {
  const PlanLayers layers = io::read_dxf_zones_file(dir_ / "zones.dxf", "zones");
  ASSERT_EQ(layers.zones.size(), 3u);
  const Zone& rectangle = layers.zones[0];
  ASSERT_EQ(rectangle.outer.size(), 4u);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(rectangle.outer)), 12.0);
  const Zone& triangle = layers.zones[1];
  EXPECT_DOUBLE_EQ(std::abs(signed_area(triangle.outer)), 18.0);
  ASSERT_EQ(triangle.holes.size(), 1u);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(triangle.holes[0])), 2.0);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(layers.zones[2].outer)), 4.0);
  // A bulged edge is its arc: 2 x 2 plus a half disk of radius 1 (72 segments a turn).
  const PlanLayers round = io::read_dxf_zones_file(dir_ / "zones.dxf", "ROUND");
  ASSERT_EQ(round.zones.size(), 1u);
  EXPECT_NEAR(std::abs(signed_area(round.zones[0].outer)), 4.0 + M_PI / 2, 0.005);
  double right = 0.0;
  for (const Eigen::Vector2d& p : round.zones[0].outer)
    right = std::max(right, p.x());
  EXPECT_NEAR(right, 3.0, 1e-9) << "the arc bulges outwards";
  // Drawing units scaled to metres.
  const PlanLayers mm = io::read_dxf_zones_file(dir_ / "zones.dxf", "ZONES", 0.001);
  EXPECT_DOUBLE_EQ(std::abs(signed_area(mm.zones[0].outer)), 12e-6);
}

TEST_F(DxfZones, AMissingLayerListsTheLayersAndAnOpenPolylineIsRefused) {
  const std::string missing =
      error_of([&] { io::read_dxf_zones_file(dir_ / "zones.dxf", "KEEPOUT"); });
  expect_contains(missing, "zones.dxf");
  expect_contains(missing, "no layer matches 'KEEPOUT'; the file has: ");
  for (const char* layer : {"OPEN", "ROUND", "WALLS", "ZONES"})
    expect_contains(missing, layer);
  const std::string open = error_of([&] { io::read_dxf_zones_file(dir_ / "zones.dxf", "OPEN"); });
  expect_contains(open, "LWPOLYLINE on layer 'OPEN' is open");
  const std::string walls = error_of([&] { io::read_dxf_zones_file(dir_ / "zones.dxf", "WALLS"); });
  expect_contains(walls, "layer 'WALLS' holds no closed LWPOLYLINE, POLYLINE or HATCH");
}

}  // namespace
}  // namespace floorgrid
