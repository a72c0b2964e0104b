// The real end-to-end case: Freiburg building 079's log (with odometry noise added), its SLAM
// map and a plan drawn wrong in places, aligned with no start and no scale given
// (tests/fixtures/fr079/dataset.yaml; the data stays in ../shared/data).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/maps/distance_field.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(Fr079, GlobalLocalizationScaleAndModelsOnARealRun) {
  FLOORGRID_REQUIRE_DATA("fr079/freiburg-079-corrected.log.gz");
  FLOORGRID_REQUIRE_DATA("fr079/floorplan.png");
  FLOORGRID_REQUIRE_DATA("fr079/slam_map.png");
  const fs::path fixture = fs::path(FLOORGRID_SOURCE_DIR) / "tests/fixtures/fr079";
  test::TempDir dir;
  const auto run = test::run_floorgrid("align '" + fixture.string() + "' --out '" +
                                       (dir / "out").string() + "'");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  std::ifstream in(dir / "out" / "metrics.json");
  const json m = json::parse(in);

  // Both starts found by global localization, within the first scans.
  EXPECT_LT(m["localization"]["grid_start_scan"].get<int>(), 50);
  // After first converging, both filters converged on at least 90% of the scans, and never
  // more than 50 scans without converging again.
  EXPECT_GE(m["pairs"]["converged_fraction"].get<double>(), 0.9);
  EXPECT_LE(m["localization"]["longest_gap_scans"].get<int>(), 50);
  // The plan's scale is estimated: the drawing is about 1.1x smaller than the SLAM map.
  EXPECT_TRUE(m["plan_scale_estimated"].get<bool>());
  EXPECT_GT(m["plan_scale"].get<double>(), 1.05);
  EXPECT_LT(m["plan_scale"].get<double>(), 1.2);
  EXPECT_GT(m["pairs"]["count"].get<int>(), 10000);
  // The walls' faces: the joint refit finds the laser meeting them 2-3 cm in front of the
  // drawing's ink, under one of its pixels (0.05 plan metres), where the ink's edges do not place
  // them, so the shift is not used (ScaleRefitOptions::min_shift_pixels). Used, it moved the
  // scale to 1.193-1.201 on seeds 1-3, 4% above the hand-made pairs' similarity (1.124);
  // kept out, 1.146-1.148.
  EXPECT_LT(std::abs(m["plan_surface_shift_m"].get<double>()),
            0.05 * m["plan_scale"].get<double>());
  EXPECT_FALSE(m["plan_surface_shift_used"].get<bool>());
  EXPECT_LT(m["plan_scale"].get<double>(), 1.17);

  // A non-rigid model puts the plan's walls within 15 cm of the SLAM map's walls wherever
  // pairs are within 2 m.
  double best = 1e9;
  for (const char* model : {"gp", "gpgt", "tps"})
    best = std::min(best, m["models"][model]["wall_distance_near_pairs_median_m"].get<double>());
  EXPECT_LE(best, 0.15);

  // The global similarity fits the corridor and the bottom room row to half a metre (the top
  // row, drawn 0.9 m too shallow, it cannot). Plan metres of floorplan.png at 0.05 m/px:
  // the corridor and the bottom rooms span y 5..13 m.
  const io::LoadedDataset d = io::load_dataset(fixture);
  const auto gt = io::read_model(dir / "out" / "model-gt.json");
  const DistanceField walls = occupied_distance_field(d.gridmap, 5.0);
  std::vector<double> distances;
  for (Eigen::Index i = 0; i < d.plan_wall_samples.cols(); ++i) {
    const Eigen::Vector2d p = d.plan_wall_samples.col(i);
    if (p.y() < 5.0 || p.y() > 13.0 || p.x() < 4.0 || p.x() > 36.0)
      continue;
    distances.push_back(walls.at(gt->forward(p)));
  }
  ASSERT_GT(distances.size(), 1000u);
  std::nth_element(distances.begin(), distances.begin() + static_cast<long>(distances.size() / 2),
                   distances.end());
  EXPECT_LE(distances[distances.size() / 2], 0.5);
}

// The submap check (off by default) on the same run, judged against the 56 hand-made pairs:
// with the defaults, seed 1's plan filter lies 1.6-2.5 m off for its first 600 scans (it starts
// where the maps' bent alignment puts it) and 1.9-2.4 m off after the turn near scan 2700, 85% of
// the scans that made pairs lie more than a metre off, and the best model's mean error is 1.28 m.
TEST(Fr079, TheSubmapCheckKeepsThePlanFilterOnTheHandMadePairs) {
  FLOORGRID_REQUIRE_DATA("fr079/freiburg-079-corrected.log.gz");
  FLOORGRID_REQUIRE_DATA("fr079/floorplan.png");
  FLOORGRID_REQUIRE_DATA("fr079/slam_map.png");
  const fs::path fixture = fs::path(FLOORGRID_SOURCE_DIR) / "tests/fixtures/fr079";
  test::TempDir dir;
  std::string manifest = test::read_file(fixture / "dataset.yaml");
  const std::string shared = "../../../../shared/data/";
  for (std::size_t at = manifest.find(shared); at != std::string::npos; at = manifest.find(shared))
    manifest.replace(at, shared.size(), test::data_path("").string() + "/");
  manifest += "truth:\n  manual_pairs: " + (fixture / "manual_pairs.csv").string() + "\n";
  test::write_file(dir / "dataset.yaml", manifest);
  test::write_file(
      dir / "on.yaml",
      "align:\n  localization:\n    dual_check:\n      submap:\n        enabled: true\n");
  const auto run =
      test::run_floorgrid("align " + test::quoted(dir / "dataset.yaml") + " --config " +
                          test::quoted(dir / "on.yaml") + " --out " + test::quoted(dir / "out"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const json m = test::read_json(dir / "out" / "metrics.json");
  EXPECT_EQ(m["sources"]["chosen"], "run");
  EXPECT_GE(m["pairs"]["converged_fraction"].get<double>(), 0.9);
  const auto& notes = m["localization"]["notes"];
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const json& n) {
    return n.get<std::string>().find("submap check: the plan filter was re-placed") !=
           std::string::npos;
  })) << notes.dump();
  // Measured 0.41 m (tps), against 1.28 m (dt) without the check.
  double best = 1e9;
  for (const char* model : {"gp", "gpgt", "tps", "dt"})
    best = std::min(best, m["models"][model]["mean_error_m"].get<double>());
  EXPECT_LT(best, 0.6);
}

}  // namespace
}  // namespace floorgrid
