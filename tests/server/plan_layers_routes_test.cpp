// The viewer's zones and waypoints routes (issue 33) through cpp-httplib's client on loopback:
// zones mapped onto the gridmap as the model maps them (a known similarity), the nav2 mask files
// on the gridmap's grid, waypoints with their heading and nav2 YAML, and every bad or hostile
// request (open, self-intersecting, degrees, NaN, off the plan or the gridmap, beyond the limits)
// answered 400/413/503 with a message naming the file and the feature, never a crash.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <thread>

#include "floorgrid/server/viewer_server.hpp"
#include "tests/support/test_data.hpp"

// Last: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>  // NOLINT(llvm-include-order)

namespace floorgrid::server {
namespace {

/// The grid point of a plan point: turned by 0.3 rad, scaled by 1.25, shifted by (4, -2).
Eigen::Vector2d truth(const Eigen::Vector2d& p) {
  return 1.25 * Eigen::Rotation2Dd(0.3).toRotationMatrix() * p + Eigen::Vector2d(4.0, -2.0);
}

std::shared_ptr<const PointMapping> model_of_truth() {
  Eigen::Matrix2Xd lattice(2, 25);
  for (int i = 0; i < 25; ++i)
    lattice.col(i) = Eigen::Vector2d(2.5 * (i % 5), 2.5 * (i / 5));
  return test::fitted("gt", test::pairs_through(truth, lattice));
}

/// A free map of width x height cells of 0.1 m from `origin`.
ViewerMap free_map(int width, int height, const Eigen::Vector2d& origin) {
  GridGeometry g;
  g.width = width;
  g.height = height;
  g.resolution = 0.1;
  g.origin = Pose2{origin.x(), origin.y(), 0.0};
  return viewer_map(OccupancyGrid(g, CellState::free));
}

/// RFC 4648 base64 decoding (the test's own, to read the answers' files).
std::string unbase64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=')
      break;
    bits = (bits << 6) | static_cast<unsigned>(alphabet.find(c));
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xff);
    }
  }
  return out;
}

/// A GeoJSON polygon feature of `ring` (closed here).
nlohmann::json polygon(const std::string& name, std::vector<Eigen::Vector2d> ring) {
  nlohmann::json coordinates = nlohmann::json::array();
  ring.push_back(ring.front());
  for (const Eigen::Vector2d& p : ring)
    coordinates.push_back({p.x(), p.y()});
  return {{"type", "Feature"},
          {"properties", {{"name", name}}},
          {"geometry", {{"type", "Polygon"}, {"coordinates", {coordinates}}}}};
}

std::vector<Eigen::Vector2d> square(double x, double y, double side) {
  const double h = side / 2;
  return {{x - h, y - h}, {x + h, y - h}, {x + h, y + h}, {x - h, y + h}};
}

nlohmann::json collection(const std::vector<nlohmann::json>& features) {
  return {{"type", "FeatureCollection"}, {"features", features}};
}

/// Whether every byte of `text` is printable ASCII.
bool printable_ascii(const std::string& text) {
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x7f || u < 0x20)
      return false;
  }
  return true;
}

class PlanLayersRoutesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ServerOptions options;
    options.port = 0;
    options.layers.max_samples = 5000;
    server_ = std::make_unique<ViewerServer>(session_, options);
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->listen(); });
  }
  void TearDown() override {
    server_->stop();
    thread_.join();
  }

  /// POSTs `body` to `path`: the status and the parsed answer.
  std::pair<int, nlohmann::json> post(const std::string& path, const std::string& body) const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    const httplib::Result r = c.Post(path, body, "application/json");
    if (!r)
      return {-1, nullptr};
    return {r->status, nlohmann::json::parse(r->body, nullptr, false)};
  }
  std::pair<int, nlohmann::json> post(const std::string& path, const nlohmann::json& body) const {
    return post(path, body.dump());
  }

  /// The plan: 10 m square from (0, 0); the gridmap: 17 x 18 m from (0, -3), holding the plan
  /// through truth().
  ViewerSession session_{model_of_truth(), "square", free_map(100, 100, {0.0, 0.0}),
                         free_map(170, 180, {0.0, -3.0})};
  std::unique_ptr<ViewerServer> server_;
  std::thread thread_;
  int port_ = 0;
};

TEST(Base64, EncodesTheRfc4648TestVectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\x00\xfe", 3)), "/wD+");
}

TEST_F(PlanLayersRoutesTest, AZoneIsMappedOntoTheGridmapAsTheModelMapsIt) {
  const auto [status, answer] = post(
      "/api/zones", nlohmann::json{{"kind", "keepout"},
                                   {"margin_sigma", 0},
                                   {"geojson", collection({polygon("bay", square(5, 5, 2))})}});
  ASSERT_EQ(status, 200) << answer.dump();
  ASSERT_EQ(answer["zones"].size(), 1u);
  const nlohmann::json& zone = answer["zones"][0];
  EXPECT_EQ(zone["name"], "bay");
  EXPECT_EQ(zone["mask_value"], 100);
  EXPECT_FALSE(zone["clipped"].get<bool>());
  // Every boundary point shown lies on the square's image: a square of side 2.5 about truth(5, 5)
  // turned by 0.3 rad.
  const Eigen::Vector2d centre = truth({5.0, 5.0});
  const Eigen::Matrix2d back = Eigen::Rotation2Dd(-0.3).toRotationMatrix();
  ASSERT_GT(zone["rings"][0].size(), 100u);
  for (const auto& p : zone["rings"][0]) {
    const Eigen::Vector2d local =
        back * (Eigen::Vector2d(p[0].get<double>(), p[1].get<double>()) - centre);
    EXPECT_NEAR(std::max(std::abs(local.x()), std::abs(local.y())), 1.25, 1e-6);
  }
  const Eigen::Vector2d first = truth({4.0, 4.0});
  EXPECT_NEAR(zone["rings"][0][0][0].get<double>(), first.x(), 1e-6);
  EXPECT_NEAR(zone["rings"][0][0][1].get<double>(), first.y(), 1e-6);
  // 6.25 m² at 0.1 m cells: 625 cells, give or take the boundary's cells.
  EXPECT_NEAR(zone["cells"].get<double>(), 625.0, 40.0);
  EXPECT_EQ(answer["mask"]["cells"], zone["cells"]);
  EXPECT_EQ(answer["filter"]["type"], 0);
  // The mask's picture: a PNG of the gridmap's size.
  const std::string png_url = answer["mask"]["png"];
  ASSERT_TRUE(png_url.starts_with("data:image/png;base64,"));
  const std::string png = unbase64(png_url.substr(22));
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) |
           (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  EXPECT_EQ(be32(16), 170u);
  EXPECT_EQ(be32(20), 180u);
}

TEST_F(PlanLayersRoutesTest, TheNav2MaskFilesHaveTheGridmapsGeometryAndTheZonesCells) {
  const nlohmann::json body{{"kind", "keepout"},
                            {"stem", "bay_mask"},
                            {"geojson", collection({polygon("bay", square(5, 5, 2))})}};
  const auto [status, answer] = post("/api/zones/nav2", body);
  ASSERT_EQ(status, 200) << answer.dump();
  const auto [zones_status, zones] = post("/api/zones", body);
  ASSERT_EQ(zones_status, 200);
  std::map<std::string, nlohmann::json> files;
  for (const auto& f : answer["files"])
    files[f["name"]] = f;
  ASSERT_EQ(files.size(), 4u) << answer.dump().substr(0, 400);
  const std::string yaml = files.at("bay_mask.yaml")["text"];
  EXPECT_NE(yaml.find("image: bay_mask.pgm"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("resolution: 0.1"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("origin: [0, -3, 0]"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("mode: trinary"), std::string::npos) << yaml;
  const std::string pgm = unbase64(files.at("bay_mask.pgm")["base64"]);
  const std::string header = "P5\n170 180\n255\n";
  ASSERT_EQ(pgm.substr(0, header.size()), header);
  ASSERT_EQ(pgm.size(), header.size() + 170u * 180u);
  const auto black = std::count(pgm.begin() + static_cast<long>(header.size()), pgm.end(), '\0');
  EXPECT_EQ(static_cast<std::size_t>(black), zones["mask"]["cells"].get<std::size_t>());
  const std::string params = files.at("bay_mask_filter_info.yaml")["text"];
  EXPECT_NE(params.find("type: 0"), std::string::npos) << params;
  const auto geojson =
      nlohmann::json::parse(files.at("bay_mask_zones_gridmap.geojson")["text"].get<std::string>());
  EXPECT_EQ(geojson["features"].size(), 1u);
}

TEST_F(PlanLayersRoutesTest, SpeedZonesTakeTheirOwnOrTheRequestsPercent) {
  nlohmann::json own = polygon("slow", square(3, 3, 1.5));
  own["properties"]["speed_percent"] = 20;
  const auto [status, answer] =
      post("/api/zones",
           nlohmann::json{{"kind", "speed"},
                          {"speed_percent", 45},
                          {"geojson", collection({own, polygon("aisle", square(7, 7, 1.5))})}});
  ASSERT_EQ(status, 200) << answer.dump();
  EXPECT_EQ(answer["filter"]["type"], 1);
  EXPECT_EQ(answer["zones"][0]["mask_value"], 20);
  EXPECT_EQ(answer["zones"][1]["mask_value"], 45);
  // Without a percent a speed zone is refused, naming it.
  const auto [refused, error] = post(
      "/api/zones", nlohmann::json{{"kind", "speed"},
                                   {"geojson", collection({polygon("aisle", square(7, 7, 1))})}});
  EXPECT_EQ(refused, 400);
  EXPECT_NE(error["error"].get<std::string>().find("'aisle'"), std::string::npos) << error.dump();
}

TEST_F(PlanLayersRoutesTest, WaypointsAreMappedWithTheirHeadingIntoTheNav2Yaml) {
  const auto [status, answer] = post(
      "/api/waypoints",
      nlohmann::json{{"csv", "name,x,y,theta\ndock,1,3,0.5\ncharger,6,2,\n"}, {"file", "w.csv"}});
  ASSERT_EQ(status, 200) << answer.dump();
  ASSERT_EQ(answer["waypoints"].size(), 2u);
  const nlohmann::json& dock = answer["waypoints"][0];
  const Eigen::Vector2d expected = truth({1.0, 3.0});
  EXPECT_EQ(dock["name"], "dock");
  EXPECT_NEAR(dock["x"].get<double>(), expected.x(), 1e-6);
  EXPECT_NEAR(dock["y"].get<double>(), expected.y(), 1e-6);
  EXPECT_NEAR(dock["theta"].get<double>(), 0.8, 1e-6);
  EXPECT_TRUE(answer["waypoints"][1]["theta"].is_null());
  const std::string yaml = answer["files"][0]["text"];
  EXPECT_EQ(answer["files"][0]["name"], "waypoints.yaml");
  char position[96];
  std::snprintf(position, sizeof(position), "position: {x: %.4f, y: %.4f, z: 0.0}", expected.x(),
                expected.y());
  EXPECT_NE(yaml.find(position), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("# dock"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find(std::to_string(std::sin(0.4)).substr(0, 7)), std::string::npos) << yaml;
  // The same from GeoJSON points, into another frame.
  const nlohmann::json point{{"type", "Feature"},
                             {"properties", {{"name", "dock"}, {"theta", 0.5}}},
                             {"geometry", {{"type", "Point"}, {"coordinates", {1.0, 3.0}}}}};
  const auto [geo_status, geo] =
      post("/api/waypoints",
           nlohmann::json{{"geojson", collection({point})}, {"frame_id", "level2/map"}});
  ASSERT_EQ(geo_status, 200) << geo.dump();
  EXPECT_NEAR(geo["waypoints"][0]["x"].get<double>(), expected.x(), 1e-6);
  EXPECT_NE(geo["files"][0]["text"].get<std::string>().find("frame_id: \"level2/map\""),
            std::string::npos);
}

TEST_F(PlanLayersRoutesTest, BadLayersGet400NamingTheFileAndTheFeature) {
  const auto zones = [](const nlohmann::json& geojson) {
    return nlohmann::json{{"file", "z.geojson"}, {"geojson", geojson}};
  };
  nlohmann::json open = polygon("open", square(5, 5, 2));
  open["geometry"]["coordinates"][0].erase(4);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {zones(collection({open})).dump(), {"z.geojson", "'open'", "open"}},
      {zones(collection({polygon("bow", {{4, 4}, {6, 6}, {6, 4}, {4, 6}})})).dump(),
       {"z.geojson", "'bow'", "self-intersecting"}},
      {zones(collection({polygon("wgs", square(13.4, 52.5, 1e-4))})).dump(),
       {"z.geojson", "degrees"}},
      {zones(R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":
          "Polygon","coordinates":[[[NaN,5],[6,5],[6,6],[NaN,5]]]}}]})")
           .dump(),
       {"z.geojson", "not JSON"}},
      {zones(collection({polygon("far", square(1000, 5, 2))})).dump(),
       {"z.geojson", "'far'", "outside the plan"}},
      {zones(collection({polygon("huge", square(5, 5, 4e7))})).dump(),
       {"z.geojson", "'huge'", "1e7"}},
      {zones(collection({polygon("beyond", square(40, 40, 2))})).dump(),
       {"z.geojson", "'beyond'", "off the gridmap"}},
      {zones(collection({})).dump(), {"z.geojson", "no zone"}},
      {nlohmann::json{{"geojson", 5}}.dump(), {"'geojson'"}},
      {nlohmann::json{{"kind", "lava"}, {"geojson", collection({})}}.dump(), {"'kind'"}},
      {nlohmann::json{{"margin_sigma", 11}, {"geojson", collection({})}}.dump(),
       {"'margin_sigma'"}},
      {nlohmann::json{{"stem", "../etc/passwd"}, {"geojson", collection({})}}.dump(), {"'stem'"}},
      {"{\"geojson\": ", {"not JSON"}},
      {"[]", {"JSON object"}},
      {"{}", {"'geojson' is missing"}},
  };
  for (const auto& [body, words] : cases) {
    for (const char* path : {"/api/zones", "/api/zones/nav2"}) {
      const auto [status, answer] = post(path, body);
      EXPECT_EQ(status, 400) << path << " " << body.substr(0, 200) << " -> " << answer.dump();
      const std::string message = answer.value("error", "");
      for (const std::string& word : words)
        EXPECT_NE(message.find(word), std::string::npos) << word << " not in: " << message;
    }
  }
  const std::vector<std::pair<nlohmann::json, std::string>> waypoint_cases = {
      {{{"csv", "name,x,y\ndock,1,nan\n"}, {"file", "w.csv"}}, "w.csv"},
      {{{"csv", "name,x,y\ndock,1\n"}, {"file", "w.csv"}}, "w.csv"},
      {{{"csv", "name,x,y\ndock,5000,3\n"}, {"file", "w.csv"}}, "outside the plan"},
      {{{"csv", "a"}, {"geojson", collection({})}}, "not both"},
      {{{"geojson", collection({polygon("bay", square(5, 5, 2))})}, {"file", "p.geojson"}},
       "no waypoint"},
      {{{"frame_id", "map\n"}, {"csv", "name,x,y\ndock,1,3\n"}}, "'frame_id'"},
      {nlohmann::json::object(), "'geojson' or 'csv' is missing"},
  };
  for (const auto& [body, word] : waypoint_cases) {
    const auto [status, answer] = post("/api/waypoints", body);
    EXPECT_EQ(status, 400) << body.dump() << " -> " << answer.dump();
    EXPECT_NE(answer.value("error", "").find(word), std::string::npos) << answer.dump();
  }
  // Still answering.
  const auto [status, answer] = post(
      "/api/zones", nlohmann::json{{"geojson", collection({polygon("bay", square(5, 5, 2))})}});
  EXPECT_EQ(status, 200) << answer.dump();
}

TEST_F(PlanLayersRoutesTest, NamesAndFileNamesAreRepeatedAsPrintableText) {
  const auto [status, answer] = post(
      "/api/zones",
      nlohmann::json{
          {"file", "b\xc3\xa4\x64\x01.geojson"},
          {"geojson", collection({polygon("b\x02\xc3\xb6w", {{4, 4}, {6, 6}, {6, 4}, {4, 6}})})}});
  ASSERT_EQ(status, 400);
  const std::string message = answer["error"];
  EXPECT_TRUE(printable_ascii(message)) << message;
  EXPECT_NE(message.find("b%C3%A4d%01.geojson"), std::string::npos) << message;
  EXPECT_NE(message.find("self-intersecting"), std::string::npos) << message;
}

TEST_F(PlanLayersRoutesTest, RequestsBeyondTheLimitsGet413BeforeTheWork) {
  // 25,000 vertices on a circle (limit 20,000): refused before the crossing check.
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i < 25000; ++i) {
    const double t = 2 * M_PI * i / 25000;
    circle.emplace_back(5 + 3 * std::cos(t), 5 + 3 * std::sin(t));
  }
  auto [status, answer] =
      post("/api/zones", nlohmann::json{{"geojson", collection({polygon("c", circle)})}});
  EXPECT_EQ(status, 413) << answer.dump();
  EXPECT_NE(answer.value("error", "").find("vertices"), std::string::npos) << answer.dump();
  // 501 zones (limit 500).
  std::vector<nlohmann::json> many;
  for (int i = 0; i < 501; ++i)
    many.push_back(
        polygon(fmt::format("z{}", i), square(0.5 + (i % 20) * 0.45, 0.5 + (i / 20) * 0.35, 0.2)));
  std::tie(status, answer) = post("/api/zones", nlohmann::json{{"geojson", collection(many)}});
  EXPECT_EQ(status, 413) << answer.dump().substr(0, 300);
  EXPECT_NE(answer.value("error", "").find("501 zones"), std::string::npos) << answer.dump();
  // A strip near the plan (within 50 m) but 90 m long: 9,200 boundary samples at 0.02 m (this
  // server: at most 5000).
  const nlohmann::json strip = polygon("wide", {{-40, 4}, {50, 4}, {50, 6}, {-40, 6}});
  std::tie(status, answer) = post("/api/zones", nlohmann::json{{"geojson", collection({strip})}});
  EXPECT_EQ(status, 413) << answer.dump();
  EXPECT_NE(answer.value("error", "").find("samples"), std::string::npos) << answer.dump();
  // A body over 2 MiB.
  std::tie(status, answer) =
      post("/api/zones", "{\"geojson\": \"" + std::string(3u << 20, ' ') + "\"}");
  EXPECT_EQ(status, 413);
  // 501 waypoints.
  std::string csv = "name,x,y\n";
  for (int i = 0; i < 501; ++i)
    csv += fmt::format("w{},1,1\n", i);
  std::tie(status, answer) = post("/api/waypoints", nlohmann::json{{"csv", csv}});
  EXPECT_EQ(status, 413) << answer.dump();
}

TEST_F(PlanLayersRoutesTest, WithoutAFreeSlotARequestIsToldToComeBack) {
  const std::string body = R"({"csv": "name,x,y\ndock,1,3\n"})";
  EXPECT_EQ(post("/api/waypoints", body).first, 200);  // this server has its two slots
  ServerOptions options;
  options.port = 0;
  options.layer_requests = 0;
  ViewerServer busy(session_, options);
  const int port = busy.bind();
  std::thread thread([&] { busy.listen(); });
  httplib::Client c("127.0.0.1", port);
  const httplib::Result r = c.Post("/api/waypoints", body, "application/json");
  busy.stop();
  thread.join();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);
  EXPECT_EQ(r->get_header_value("Retry-After"), "1");
  EXPECT_NE(r->body.find("busy"), std::string::npos) << r->body;
}

}  // namespace
}  // namespace floorgrid::server
