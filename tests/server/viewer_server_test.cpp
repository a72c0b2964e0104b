// The viewer's HTTP API, through cpp-httplib's client on loopback: points mapped as the model
// maps them (a known similarity), the robot pose fed back, every bad request answered with a
// 4xx and a message naming the field, static files only from the web root, and requests safe
// while a refit swaps the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/server/viewer_server.hpp"
#include "tests/support/test_data.hpp"

// Last: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>  // NOLINT(llvm-include-order)

namespace floorgrid::server {
namespace {

/// The grid point of a plan point under the similarity: scale s, turned by theta, shifted.
struct Similarity {
  double s, theta, tx, ty;
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
    return s * Eigen::Rotation2Dd(theta).toRotationMatrix() * p + Eigen::Vector2d(tx, ty);
  }
};

/// A gt model fitted to exact pairs of `truth` on a 10 m square.
std::shared_ptr<const PointMapping> model_of(const Similarity& truth) {
  Eigen::Matrix2Xd lattice(2, 25);
  for (int i = 0; i < 25; ++i)
    lattice.col(i) = Eigen::Vector2d(2.5 * (i % 5), 2.5 * (i / 5));
  return test::fitted("gt", test::pairs_through(truth, lattice));
}

/// A 40 x 30 cell map at 0.1 m, origin (-1, 2): free, one occupied cell at (3, 5), its top
/// row unknown.
OccupancyGrid small_map() {
  GridGeometry g;
  g.width = 40;
  g.height = 30;
  g.resolution = 0.1;
  g.origin = Pose2{-1.0, 2.0, 0.0};
  OccupancyGrid grid(g, CellState::free);
  grid.set_state(3, 5, CellState::occupied);
  for (int ix = 0; ix < g.width; ++ix)
    grid.set_state(ix, g.height - 1, CellState::unknown);
  return grid;
}

const Similarity kTruth{1.25, 0.3, 4.0, -2.0};
const Similarity kOtherTruth{0.8, -0.5, -1.0, 3.0};

class ViewerServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        std::filesystem::temp_directory_path() /
        ("floorgrid-viewer-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_ / "web");
    std::ofstream(root_ / "web" / "index.html") << "<!doctype html><title>floorgrid</title>";
    std::ofstream(root_ / "secret.txt") << "not for the web";
    std::filesystem::create_directories(root_ / "lib");
    std::ofstream(root_ / "lib" / "lib.js") << "// a library";
    ServerOptions options;
    options.port = 0;
    options.static_files = {{"/", root_ / "web"}, {"/vendor/lib/", root_ / "lib"}};
    options.limits.max_points = 1000;
    server_ = std::make_unique<ViewerServer>(session_, options);
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->listen(); });
  }

  void TearDown() override {
    server_->stop();
    thread_.join();
    std::filesystem::remove_all(root_);
  }

  httplib::Client client() const { return httplib::Client("127.0.0.1", port_); }

  /// POSTs `body` to /api/map; the status and the parsed answer.
  std::pair<int, nlohmann::json> post_map(const std::string& body) const {
    httplib::Client c = client();
    const httplib::Result r = c.Post("/api/map", body, "application/json");
    if (!r)
      return {-1, nullptr};
    return {r->status, nlohmann::json::parse(r->body, nullptr, false)};
  }

  ViewerSession session_{model_of(kTruth), "square", viewer_map(small_map())};
  std::filesystem::path root_;
  std::unique_ptr<ViewerServer> server_;
  std::thread thread_;
  int port_ = 0;
};

TEST_F(ViewerServerTest, MapsPointsAndPosesBothWaysAsTheModelDoes) {
  const auto [status, answer] =
      post_map(R"({"from": "plan", "points": [[1.0, 2.0], [3.0, 4.0, 0.5]]})");
  ASSERT_EQ(status, 200) << answer.dump();
  EXPECT_EQ(answer["to"], "grid");
  EXPECT_EQ(answer["model"], "gt");
  ASSERT_EQ(answer["points"].size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d expected = kTruth(i == 0 ? Eigen::Vector2d(1, 2) : Eigen::Vector2d(3, 4));
    EXPECT_NEAR(answer["points"][i]["x"].get<double>(), expected.x(), 1e-6);
    EXPECT_NEAR(answer["points"][i]["y"].get<double>(), expected.y(), 1e-6);
    EXPECT_EQ(answer["points"][i]["flag"], "ok");
    EXPECT_FALSE(answer["points"][i]["extrapolated"].get<bool>());
  }
  EXPECT_FALSE(answer["points"][0].contains("theta"));
  EXPECT_NEAR(answer["points"][1]["theta"].get<double>(), 0.5 + kTruth.theta, 1e-6);

  // Back from the grid, and a point far beyond every pair flagged.
  const Eigen::Vector2d g = kTruth(Eigen::Vector2d(5.0, 6.0));
  const auto [back_status, back] =
      post_map(R"({"from": "grid", "points": [[)" + std::to_string(g.x()) + "," +
               std::to_string(g.y()) + R"(], [500, 500]]})");
  ASSERT_EQ(back_status, 200) << back.dump();
  EXPECT_NEAR(back["points"][0]["x"].get<double>(), 5.0, 1e-5);
  EXPECT_NEAR(back["points"][0]["y"].get<double>(), 6.0, 1e-5);
  EXPECT_TRUE(back["points"][1]["extrapolated"].get<bool>());
}

TEST_F(ViewerServerTest, EveryBadRequestGetsAClientErrorNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "not JSON"},
      {"[1, 2]", "JSON object"},
      {R"({"points": [[1, 2]]})", "'from'"},
      {R"({"from": "moon", "points": [[1, 2]]})", "'from'"},
      {R"({"from": "plan"})", "'points'"},
      {R"({"from": "plan", "points": {"x": 1}})", "'points'"},
      {R"({"from": "plan", "points": [[1]]})", "'points[0]'"},
      {R"({"from": "plan", "points": [[1, 2], [1, "2"]]})", "'points[1]' y"},
      {R"({"from": "plan", "points": [[1, 2, 3, 4]]})", "'points[0]'"},
      {R"({"from": "plan", "points": [[NaN, 2]]})", "not JSON"},
      {R"({"from": "plan", "points": [[1e999, 2]]})", "not JSON"},
      {R"({"from": "plan", "points": [[1, 2]], "model": "tps"})", "'model'"},
  };
  for (const auto& [body, says] : cases) {
    const auto [status, answer] = post_map(body);
    EXPECT_EQ(status, 400) << body;
    ASSERT_TRUE(answer.is_object() && answer.contains("error")) << body;
    EXPECT_NE(answer["error"].get<std::string>().find(says), std::string::npos)
        << body << " -> " << answer.dump();
  }
  httplib::Client c = client();
  const httplib::Result pose = c.Post("/api/robot_pose", R"({"x": 1, "y": 2})", "application/json");
  ASSERT_TRUE(pose);
  EXPECT_EQ(pose->status, 400);
  EXPECT_NE(pose->body.find("'theta'"), std::string::npos) << pose->body;
}

TEST_F(ViewerServerTest, TooManyPointsOrTooLargeABodyGet413) {
  // Over the points limit (1000 here), in a small body.
  std::string body = R"({"from": "plan", "points": [)";
  for (int i = 0; i < 1001; ++i)
    body += i ? ",[1,2]" : "[1,2]";
  body += "]}";
  const auto [status, answer] = post_map(body);
  EXPECT_EQ(status, 413);
  EXPECT_NE(answer.dump().find("1001"), std::string::npos) << answer.dump();

  // 10^7 points: the body alone is over the 8 MiB limit and is never parsed.
  std::string huge = R"({"from": "plan", "points": [)";
  huge.reserve(60'000'100);
  for (int i = 0; i < 10'000'000; ++i)
    huge += i ? ",[1,2]" : "[1,2]";
  huge += "]}";
  const auto [huge_status, huge_answer] = post_map(huge);
  EXPECT_EQ(huge_status, 413) << huge_answer.dump();

  // A JSON body sent as a form (curl -d's default) over the HTTP library's 8 KiB form limit:
  // the routes read their bodies themselves, so it is taken as JSON.
  std::string points = R"({"from": "plan", "points": [)";
  for (int i = 0; i < 900; ++i)
    points += i ? ",[1.25,2.5]" : "[1.25,2.5]";
  points += "]}";
  httplib::Client c = client();
  const httplib::Result form = c.Post("/api/map", points, "application/x-www-form-urlencoded");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 200) << form->body;
  EXPECT_EQ(c.Post("/api/map", points, "application/json")->status, 200);

  // The server still answers.
  EXPECT_EQ(post_map(R"({"from": "plan", "points": [[1, 2]]})").first, 200);
}

TEST_F(ViewerServerTest, StaticFilesComeOnlyFromTheWebRoot) {
  httplib::Client c = client();
  const httplib::Result index = c.Get("/index.html");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_NE(index->body.find("floorgrid"), std::string::npos);
  const httplib::Result library = c.Get("/vendor/lib/lib.js");
  ASSERT_TRUE(library);
  EXPECT_EQ(library->status, 200);
  EXPECT_EQ(library->body, "// a library");
  for (const char* path :
       {"/../secret.txt", "/%2e%2e/secret.txt", "/..%2fsecret.txt", "/web/../../secret.txt",
        "/nothing-here.js", "/vendor/lib/../../secret.txt", "/vendor/lib/%2e%2e/%2e%2e/secret.txt",
        "/lib/lib.js"}) {
    const httplib::Result r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_EQ(r->body.find("not for the web"), std::string::npos) << path;
  }
}

TEST_F(ViewerServerTest, MapsComeAsPngsWithTheirPlaceInMetres) {
  httplib::Client c = client();
  const nlohmann::json info = nlohmann::json::parse(c.Get("/api/info")->body);
  EXPECT_EQ(info["dataset"], "square");
  EXPECT_EQ(info["plan"]["width"], 40);
  EXPECT_EQ(info["plan"]["height"], 30);
  EXPECT_DOUBLE_EQ(info["plan"]["resolution"].get<double>(), 0.1);
  EXPECT_NEAR(info["plan"]["bounds"][0][0].get<double>(), -1.0, 1e-12);
  EXPECT_NEAR(info["plan"]["bounds"][0][1].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(info["plan"]["bounds"][1][0].get<double>(), 3.0, 1e-12);
  EXPECT_NEAR(info["plan"]["bounds"][1][1].get<double>(), 5.0, 1e-12);
  EXPECT_TRUE(info["grid"].is_null());  // this session has no gridmap picture

  const httplib::Result png = c.Get("/api/maps/plan.png");
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  const std::filesystem::path file = root_ / "plan.png";
  std::ofstream(file, std::ios::binary) << png->body;
  const io::GreyImage image = io::read_grey_image(file);
  ASSERT_EQ(image.width, 40);
  ASSERT_EQ(image.height, 30);
  // Top row first: cell (3, 5) is image row 30 - 1 - 5; the top row is unknown.
  EXPECT_EQ(image.level[static_cast<std::size_t>(24 * 40 + 3)], 0);
  EXPECT_EQ(image.level[static_cast<std::size_t>(10 * 40 + 10)], 254);
  EXPECT_EQ(image.level[5], 205);
  const httplib::Result none = c.Get("/api/maps/grid.png");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 404);
  EXPECT_NE(none->body.find("no grid map"), std::string::npos) << none->body;
}

TEST_F(ViewerServerTest, ManualPairsAddedAndDeletedThenARefitMapsByThem) {
  httplib::Client c = client();
  // Four pairs of the other similarity, one more that is deleted again.
  std::vector<std::uint64_t> ids;
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(8, 0), Eigen::Vector2d(0, 6), Eigen::Vector2d(8, 6),
        Eigen::Vector2d(4, 3)}) {
    const Eigen::Vector2d g = ids.size() == 4 ? Eigen::Vector2d(99, 99) : kOtherTruth(p);
    const nlohmann::json pair = {{"plan", {p.x(), p.y()}}, {"grid", {g.x(), g.y()}}};
    const httplib::Result r = c.Post("/api/pairs", pair.dump(), "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 201) << r->body;
    ids.push_back(nlohmann::json::parse(r->body)["id"].get<std::uint64_t>());
  }
  const std::string last = "/api/pairs/" + std::to_string(ids.back());
  ASSERT_EQ(c.Delete(last.c_str())->status, 200);
  EXPECT_EQ(c.Delete(last.c_str())->status, 404);  // gone already
  const nlohmann::json listed = nlohmann::json::parse(c.Get("/api/pairs")->body);
  ASSERT_EQ(listed["pairs"].size(), 4u);
  EXPECT_EQ(listed["pairs"][1]["plan"][0], 8.0);

  const httplib::Result fit = c.Post("/api/fit", R"({"model": "gt"})", "application/json");
  ASSERT_TRUE(fit);
  ASSERT_EQ(fit->status, 200) << fit->body;
  EXPECT_EQ(nlohmann::json::parse(fit->body)["pairs"], 4);
  const auto [status, answer] = post_map(R"({"from": "plan", "points": [[2.0, 5.0]]})");
  ASSERT_EQ(status, 200);
  const Eigen::Vector2d expected = kOtherTruth(Eigen::Vector2d(2, 5));
  EXPECT_NEAR(answer["points"][0]["x"].get<double>(), expected.x(), 1e-6);
  EXPECT_NEAR(answer["points"][0]["y"].get<double>(), expected.y(), 1e-6);

  // Bad pairs and fits: a 400 naming the field, the model left as it was.
  for (const auto& [path, body, says] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"/api/pairs", R"({"plan": [1, 2]})", "'grid'"},
           {"/api/pairs", R"({"plan": [1], "grid": [1, 2]})", "'plan'"},
           {"/api/pairs", R"({"plan": [1, 2], "grid": [1, null]})", "'grid' y"},
           {"/api/fit", R"({"model": "magic"})", "'model'"},
           {"/api/fit", R"({})", "'model'"}}) {
    const httplib::Result r = c.Post(path.c_str(), body, "application/json");
    ASSERT_TRUE(r) << body;
    EXPECT_EQ(r->status, 400) << body;
    EXPECT_NE(r->body.find(says), std::string::npos) << body << " -> " << r->body;
  }
  EXPECT_EQ(c.Delete("/api/pairs/abc")->status, 404);
  for (const std::uint64_t id : {ids[0], ids[1], ids[2]})
    c.Delete(("/api/pairs/" + std::to_string(id)).c_str());
  const httplib::Result too_few = c.Post("/api/fit", R"({"model": "gt"})", "application/json");
  ASSERT_TRUE(too_few);
  EXPECT_EQ(too_few->status, 400) << too_few->body;
  EXPECT_EQ(post_map(R"({"from": "plan", "points": [[2.0, 5.0]]})").second["points"][0]["x"],
            answer["points"][0]["x"]);
}

TEST_F(ViewerServerTest, ARobotPosePostedIsTheOneServed) {
  httplib::Client c = client();
  const httplib::Result none = c.Get("/api/robot_pose");
  ASSERT_TRUE(none);
  EXPECT_EQ(nlohmann::json::parse(none->body)["sequence"], 0);
  const httplib::Result posted =
      c.Post("/api/robot_pose", R"({"x": 1.5, "y": -2.0, "theta": 0.25})", "application/json");
  ASSERT_TRUE(posted);
  ASSERT_EQ(posted->status, 200) << posted->body;
  EXPECT_EQ(nlohmann::json::parse(posted->body)["sequence"], 1);
  const nlohmann::json pose = nlohmann::json::parse(c.Get("/api/robot_pose")->body);
  EXPECT_EQ(pose["sequence"], 1);
  EXPECT_DOUBLE_EQ(pose["x"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(pose["y"].get<double>(), -2.0);
  EXPECT_DOUBLE_EQ(pose["theta"].get<double>(), 0.25);
  EXPECT_EQ(nlohmann::json::parse(c.Get("/api/info")->body)["robot_pose_sequence"], 1);
  // On the plan: where the similarity puts the grid pose back, turned back by its angle.
  const Eigen::Vector2d on_plan =
      Eigen::Rotation2Dd(-kTruth.theta).toRotationMatrix() *
      (Eigen::Vector2d(1.5, -2.0) - Eigen::Vector2d(kTruth.tx, kTruth.ty)) / kTruth.s;
  EXPECT_NEAR(pose["plan"]["x"].get<double>(), on_plan.x(), 1e-6);
  EXPECT_NEAR(pose["plan"]["y"].get<double>(), on_plan.y(), 1e-6);
  EXPECT_NEAR(pose["plan"]["theta"].get<double>(), 0.25 - kTruth.theta, 1e-6);
  EXPECT_TRUE(pose["plan"]["flag"].is_string());
  EXPECT_TRUE(pose["plan"]["nearest_pair_m"].is_number());
  EXPECT_TRUE(pose["plan"]["extrapolated"].is_boolean());
}

TEST_F(ViewerServerTest, TheAlignmentsPairsAreListedOnAskingThinnedToTheLimit) {
  ReferencePairs base;
  base.points_in_plan.resize(2, 25'000);
  base.points_in_grid.resize(2, 25'000);
  for (Eigen::Index i = 0; i < base.points_in_plan.cols(); ++i) {
    base.points_in_plan.col(i) = Eigen::Vector2d(0.001 * i, 1.0);
    base.points_in_grid.col(i) = kTruth(base.points_in_plan.col(i));
  }
  session_.set_base_pairs(base);
  httplib::Client c = client();
  const nlohmann::json plain = nlohmann::json::parse(c.Get("/api/pairs")->body);
  EXPECT_EQ(plain["base_pairs"], 25'000);
  EXPECT_FALSE(plain.contains("base"));
  const nlohmann::json listed = nlohmann::json::parse(c.Get("/api/pairs?base=1")->body);
  ASSERT_EQ(listed["base"].size(), 20'000u);
  // Evenly thinned: the k-th shown is pair k * n / shown, and its grid point is that pair's.
  const nlohmann::json& shown = listed["base"][10'000];
  EXPECT_DOUBLE_EQ(shown[0].get<double>(), 0.001 * 12'500);
  const Eigen::Vector2d g = kTruth(Eigen::Vector2d(0.001 * 12'500, 1.0));
  EXPECT_DOUBLE_EQ(shown[2].get<double>(), g.x());
  EXPECT_DOUBLE_EQ(shown[3].get<double>(), g.y());
  const httplib::Result bad = c.Get("/api/pairs?base=yes");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("'base'"), std::string::npos) << bad->body;
}

TEST_F(ViewerServerTest, ARefitStatesItsCrossValidatedErrorAndStdAsFitDoes) {
  // 400 pairs of the other similarity over 20 x 20 m, each off by up to 5 cm.
  ReferencePairs base;
  base.points_in_plan.resize(2, 400);
  base.points_in_grid.resize(2, 400);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  for (Eigen::Index i = 0; i < 400; ++i) {
    base.points_in_plan.col(i) = Eigen::Vector2d(i % 20, i / 20);
    base.points_in_grid.col(i) =
        kOtherTruth(base.points_in_plan.col(i)) + Eigen::Vector2d(noise(rng), noise(rng));
  }
  session_.set_base_pairs(base);
  httplib::Client c = client();
  const httplib::Result fit = c.Post("/api/fit", R"({"model": "gt"})", "application/json");
  ASSERT_TRUE(fit);
  ASSERT_EQ(fit->status, 200) << fit->body;
  const nlohmann::json summary = nlohmann::json::parse(fit->body);
  EXPECT_EQ(summary["has_std_m"], true);
  // The held-out error of a similarity fitted to pairs off by at most 5 cm.
  EXPECT_GT(summary["cv_error_m"].get<double>(), 0.0);
  EXPECT_LT(summary["cv_error_m"].get<double>(), 0.07);
  const auto [status, answer] = post_map(R"({"from": "plan", "points": [[10.0, 10.0]]})");
  ASSERT_EQ(status, 200);
  ASSERT_TRUE(answer["points"][0]["std_m"].is_number()) << answer.dump();
  EXPECT_GT(answer["points"][0]["std_m"].get<double>(), 0.0);
  EXPECT_LT(answer["points"][0]["std_m"].get<double>(), 0.1);
}

TEST_F(ViewerServerTest, LayersAreDrawnOncePerModelAndAgainAfterARefit) {
  httplib::Client c = client();
  // Without a renderer: no layers, said so.
  EXPECT_EQ(nlohmann::json::parse(c.Get("/api/info")->body)["layers"]["heatmap"], false);
  EXPECT_EQ(c.Get("/api/heatmap")->status, 404);
  EXPECT_EQ(c.Get("/api/overlay.png")->status, 404);

  std::atomic<int> drawn = 0;
  session_.set_layer_renderer([&drawn](const PointMapping& model) {
    ++drawn;
    ModelLayers layers;
    layers.overlay_png = "overlay of " + model.name();
    layers.heat.push_back({"std", "std_m", 0.5, "std of " + model.name()});
    return layers;
  });
  const nlohmann::json info = nlohmann::json::parse(c.Get("/api/info")->body);
  EXPECT_EQ(info["layers"]["overlay"], true);
  EXPECT_EQ(info["model_version"], 1);
  EXPECT_NE(std::find(info["models"].begin(), info["models"].end(), "tps"), info["models"].end());
  const nlohmann::json heat = nlohmann::json::parse(c.Get("/api/heatmap")->body);
  ASSERT_EQ(heat["layers"].size(), 1u);
  EXPECT_EQ(heat["layers"][0]["kind"], "std");
  EXPECT_EQ(heat["layers"][0]["clip_m"], 0.5);
  EXPECT_EQ(heat["layers"][0]["url"], "/api/heatmap.png?kind=std&v=1");
  EXPECT_EQ(c.Get("/api/heatmap.png?kind=std")->body, "std of gt");
  EXPECT_EQ(c.Get("/api/overlay.png")->body, "overlay of gt");
  const httplib::Result unknown = c.Get("/api/heatmap.png?kind=error");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  EXPECT_NE(unknown->body.find("std"), std::string::npos) << unknown->body;
  EXPECT_EQ(drawn, 1);  // one drawing served every request of this model

  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0, 0), Eigen::Vector2d(8, 0),
                                   Eigen::Vector2d(0, 6), Eigen::Vector2d(8, 6)}) {
    const Eigen::Vector2d g = kOtherTruth(p);
    const nlohmann::json pair = {{"plan", {p.x(), p.y()}}, {"grid", {g.x(), g.y()}}};
    ASSERT_EQ(c.Post("/api/pairs", pair.dump(), "application/json")->status, 201);
  }
  ASSERT_EQ(c.Post("/api/fit", R"({"model": "gt-affine"})", "application/json")->status, 200);
  EXPECT_EQ(nlohmann::json::parse(c.Get("/api/info")->body)["model_version"], 2);
  EXPECT_EQ(nlohmann::json::parse(c.Get("/api/heatmap")->body)["layers"][0]["url"],
            "/api/heatmap.png?kind=std&v=2");
  EXPECT_EQ(c.Get("/api/overlay.png")->body, "overlay of gt-affine");
  EXPECT_EQ(drawn, 2);
}

TEST_F(ViewerServerTest, RequestsWhileARefitSwapsTheModelMapByOneModelEach) {
  const std::shared_ptr<const PointMapping> models[] = {model_of(kTruth), model_of(kOtherTruth)};
  std::string body = R"({"from": "plan", "points": [)";
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 100; ++i) {
    points.emplace_back(0.1 * i, 10.0 - 0.1 * i);
    const nlohmann::json point = {points.back().x(), points.back().y()};
    body += (i ? "," : "");
    body += point.dump();
  }
  body += "]}";
  std::atomic<bool> done = false;
  std::atomic<int> errors = 0, mixed = 0, answered = 0;
  std::vector<std::thread> clients;
  for (int t = 0; t < 4; ++t) {
    clients.emplace_back([&] {
      for (int k = 0; k < 40; ++k) {
        const auto [status, answer] = post_map(body);
        if (status != 200) {
          ++errors;
          continue;
        }
        // Every point by the same one of the two truths.
        int by_first = 0, by_second = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
          const Eigen::Vector2d got(answer["points"][i]["x"].get<double>(),
                                    answer["points"][i]["y"].get<double>());
          by_first += (got - kTruth(points[i])).norm() < 1e-6;
          by_second += (got - kOtherTruth(points[i])).norm() < 1e-6;
        }
        mixed += !(by_first == 100 || by_second == 100);
        ++answered;
      }
    });
  }
  for (int swap = 0; !done; ++swap) {
    session_.set_model(models[swap % 2]);
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    done = answered + errors >= 160;
  }
  for (std::thread& t : clients)
    t.join();
  EXPECT_EQ(errors, 0);
  EXPECT_EQ(mixed, 0);
  EXPECT_EQ(answered, 160);
}

}  // namespace
}  // namespace floorgrid::server
