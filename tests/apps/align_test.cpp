// `floorgrid align` and `floorgrid pairs` end to end on simulated buildings, against the
// simulator's exact truth: from the noisy odometry in the log, with the plan's scale unknown.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/io/report/report_format.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quoted;
using test::read_json;
using test::run_floorgrid;
using test::TempDir;

/// Simulates `preset` and aligns it; returns metrics.json. `models`, when given (a YAML list
/// such as `["gt"]`), are the only models fitted: a test that reads one model's numbers need not
/// wait for the others (the pairs do not depend on them).
json simulate_and_align(const std::string& preset, int seed, const TempDir& dir,
                        const std::string& models = "") {
  const auto sim = run_floorgrid("simulate --preset " + preset + " --seed " + std::to_string(seed) +
                                 " --out " + quoted(dir / "data"));
  EXPECT_EQ(sim.status, 0) << sim.err;
  std::string config;
  if (!models.empty()) {
    test::write_file(dir / "models.yaml", "align:\n  models:\n    models: " + models + "\n");
    config = " --config " + quoted(dir / "models.yaml");
  }
  const auto run =
      run_floorgrid("align " + quoted(dir / "data") + config + " --out " + quoted(dir / "out"));
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  return read_json(dir / "out" / "metrics.json");
}

/// SPEC's `plan_scale` (world metres per plan metre) of a simulated dataset.
double true_plan_scale(const TempDir& dir) {
  return read_json(dir / "data" / "truth.json")["plan"]["plan_scale"].get<double>();
}

TEST(AlignCommand, OfficeGivesAccuratePairsAndModelsAndEveryContractKey) {
  TempDir dir;
  const json m = simulate_and_align("office", 1, dir);
  // metrics.json: SPEC's keys (a contract).
  for (const char* reason : {"not_converged", "no_return", "off_plan_wall", "off_grid_wall",
                             "subsampled", "per_scan_cap"}) {
    EXPECT_TRUE(m["pairs"]["rejected"].contains(reason)) << reason;
  }
  for (const char* key : {"count", "converged_fraction", "error_median_m"})
    EXPECT_TRUE(m["pairs"].contains(key)) << key;
  EXPECT_EQ(m["domain"]["kind"], "warp");
  // The folder is a finished result: no INCOMPLETE.txt (written while align writes, removed at
  // the end; an interrupted run rewrites it: HardeningCli.AnInterruptedAlignSaysSoInItsFolder).
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "INCOMPLETE.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "metrics.json"));
  EXPECT_GT(m["domain"]["points"].get<int>(), 1000);
  // The plan scale the truth gives over the domain: the simulated office's own (its gridmap's
  // drift moves it by 5e-6), not its inverse (1.5% off here). bench/real_matrix.sh judges the
  // run's estimate against it.
  EXPECT_NEAR(m["domain"]["truth_plan_scale"].get<double>(), true_plan_scale(dir),
              0.001 * true_plan_scale(dir));
  // Which dataset was aligned (what `serve` of the folder shows).
  EXPECT_TRUE(std::filesystem::equivalent(m["dataset_path"].get<std::string>(),
                                          dir / "data" / "dataset.yaml"))
      << m["dataset_path"];
  for (const char* key : {"load", "global_localization", "scale_search", "localize", "pairs", "fit",
                          "evaluate", "write"}) {
    EXPECT_TRUE(m["timings_s"].contains(key)) << key;
  }
  // The peak memory at each stage's end: it only grows, and a process that read the dataset
  // holds more than a few MiB and less than the machine (the office peaks near 150 MiB).
  double before = 0.0;
  for (const char* stage : {"load", "maps_alignment", "localize", "fit", "write"}) {
    ASSERT_TRUE(m["peak_memory_mib"].contains(stage)) << stage;
    const double mib = m["peak_memory_mib"][stage].get<double>();
    EXPECT_GE(mib, before) << stage;
    before = mib;
  }
  EXPECT_GT(m["peak_memory_mib"]["load"].get<double>(), 5.0);
  EXPECT_LT(m["peak_memory_mib"]["write"].get<double>(), 4096.0);
  for (const char* model : {"gt", "gp", "gpgt", "ct", "dt", "tps", "lc", "auto"}) {
    const json& j = m["models"][model];
    for (const char* key :
         {"mean_error_m", "median_error_m", "p95_error_m", "fit_seconds", "cv_error_m"}) {
      EXPECT_TRUE(j.contains(key) && j[key].is_number()) << model << "." << key;
    }
    for (const char* key : {"min_m", "mean_m", "max_m"})
      EXPECT_TRUE(j["back_and_forth"][key].is_number()) << model << ".back_and_forth." << key;
    // There and back 100 times: every model drifts at most 1e-6 m (issue 13's bar; the Newton
    // inverse stops at 1e-11 of the extent, dt and lc invert exactly). A point where the map
    // folds or jumps has more than one plan point: it is counted not invertible, never
    // returned elsewhere. Most points come back.
    EXPECT_LE(j["back_and_forth"]["max_m"].get<double>(), 1e-6) << model;
    EXPECT_LE(
        j["back_and_forth"]["not_invertible"].get<double>(),
        (std::string(model) == "lc" ? 0.2 : 0.02) * j["back_and_forth"]["points"].get<double>())
        << model;
    // Which cross-validation cv_error_m is: spatially blocked by default; auto's is the runs
    // it compared the models by.
    EXPECT_EQ(j["cv_folds"], 5) << model;
    if (std::string(model) == "auto") {
      EXPECT_EQ(j["cv_kind"], "runs");
      EXPECT_TRUE(j["cv_block_m"].is_null());
    } else {
      EXPECT_EQ(j["cv_kind"], "blocked") << model;
      EXPECT_GT(j["cv_block_m"].get<double>(), 0.0) << model;
    }
    // Every model's std_m carries the bias the pairs share, as measured once for all.
    EXPECT_EQ(j["uncertainty"]["shared_std_m"], m["shared_bias"]["std_m"]) << model;
    EXPECT_TRUE(fs::exists(dir / "out" / ("model-" + std::string(model) + ".json"))) << model;
    EXPECT_TRUE(fs::exists(dir / "out" / "overlays" / ("overlay-" + std::string(model) + ".png")));
  }
  EXPECT_TRUE(fs::exists(dir / "out" / "model.json"));
  // That bias: the run's pairs and the maps' alignment agree, so how far apart they lie, per
  // place (less than pair by pair: a pair's own noise drops out); no faces' part (the office's
  // plan is drawn as vectors: the faces are fitted on raster plans).
  ASSERT_EQ(m["sources"]["agreement"]["agree"], true);
  EXPECT_EQ(m["shared_bias"]["from"], "agreement");
  EXPECT_EQ(m["shared_bias"]["sources_m"], m["sources"]["agreement"]["local_median_m"]);
  EXPECT_EQ(m["shared_bias"]["faces_m"], 0.0);
  EXPECT_EQ(m["shared_bias"]["std_m"], m["shared_bias"]["sources_m"]);
  EXPECT_GT(m["shared_bias"]["std_m"].get<double>(), 0.0);
  EXPECT_LT(m["sources"]["agreement"]["local_median_m"].get<double>(),
            m["sources"]["agreement"]["median_m"].get<double>());
  // Each filter's track, a row per scan of the log.
  std::ifstream scans(dir / "out" / "scans.csv");
  std::string header;
  std::getline(scans, header);
  EXPECT_EQ(header.rfind("scan,time,plan_x,plan_y,plan_theta,plan_state", 0), 0u) << header;

  // report.html: a sample of metrics.json's numbers, as the report formats them.
  const std::string report = test::read_file(dir / "out" / "report.html");
  EXPECT_NE(report.find("<section id=\"summary\">"), std::string::npos);
  const std::string chosen = m["chosen_model"].get<std::string>();
  for (const std::string& expected :
       {io::format_metres(m["models"][chosen]["mean_error_m"]),
        io::format_metres(m["models"][chosen]["cv_error_m"]),
        io::format_metres(m["models"]["gt"]["p95_error_m"]),
        io::format_metres(m["models"]["tps"]["median_error_m"]),
        io::format_metres(m["models"]["dt"]["back_and_forth"]["max_m"]),
        io::format_count(m["pairs"]["count"]),
        io::format_count(m["pairs"]["rejected"]["off_plan_wall"]),
        io::format_percent(m["pairs"]["converged_fraction"]), io::format_ratio(m["plan_scale"]),
        io::format_seconds(m["timings_s"]["localize"]), io::format_count(m["domain"]["points"])}) {
    EXPECT_NE(report.find(expected), std::string::npos) << expected;
  }
  EXPECT_TRUE(fs::exists(dir / "out" / "overlays" / "pairs.png"));

  // Accuracy against the exact warp (issue: pairs median <= 5 cm, gt <= 10 cm).
  EXPECT_LE(m["pairs"]["error_median_m"].get<double>(), 0.05);
  EXPECT_GE(m["pairs"]["converged_fraction"].get<double>(), 0.9);
  EXPECT_LE(m["models"]["gt"]["mean_error_m"].get<double>(), 0.10);
  EXPECT_NEAR(m["plan_scale"].get<double>(), true_plan_scale(dir), 0.002);
  // The pairs' own noise, measured between visits without the truth, is of the size of their
  // error against the truth (their mean error 0.056 m here; the noise leaves out what every
  // visit to a place shares).
  ASSERT_TRUE(m["pairs"]["noise_rms_m"].is_number());
  EXPECT_GT(m["pairs"]["noise_differences"].get<int>(), 1000);
  EXPECT_GT(m["pairs"]["noise_rms_m"].get<double>(),
            0.5 * m["pairs"]["error_mean_m"].get<double>());
  EXPECT_LT(m["pairs"]["noise_rms_m"].get<double>(),
            2.0 * m["pairs"]["error_mean_m"].get<double>());
  // The wall slide says what it measured, and the files agree with whether pairs slid.
  const json& slide = m["pairs"]["wall_slide"];
  ASSERT_TRUE(slide.is_object());
  ASSERT_TRUE(slide["noise_along_m"].is_number() && slide["noise_across_m"].is_number());
  const bool slid = slide["applied"].get<bool>();
  EXPECT_EQ(slid,
            slide["noise_along_m"].get<double>() >= 1.5 * slide["noise_across_m"].get<double>());
  EXPECT_EQ(fs::exists(dir / "out" / "pairs-localized.csv"), slid);
  // The pairs file holds the pairs counted.
  const ReferencePairs pairs = io::read_pairs_csv(dir / "out" / "pairs.csv");
  EXPECT_EQ(pairs.size(), m["pairs"]["count"].get<Eigen::Index>());
  // The model chosen by auto maps points; its file loads.
  const auto map = run_floorgrid("map --model " + quoted(dir / "out" / "model.json") + " 10,5");
  EXPECT_EQ(map.status, 0) << map.err;
}

TEST(AlignCommand, APlanRefusedByTheMatchGetsNoModels) {
  // The office's own plan, held to a match no plan reaches: as a plan of another building, it
  // ends with exit 3, the localization's story written and no model file to pick up.
  TempDir dir;
  ASSERT_EQ(run_floorgrid("simulate --preset office --seed 1 --out " + quoted(dir / "data")).status,
            0);
  test::write_file(dir / "strict.yaml",
                   "align:\n  localization:\n    plan_location:\n      min_plan_match: 0.99\n");
  const auto run = run_floorgrid("align " + quoted(dir / "data") + " --config " +
                                 quoted(dir / "strict.yaml") + " --out " + quoted(dir / "out"));
  EXPECT_EQ(run.status, 3) << run.out << run.err;
  EXPECT_NE(run.err.find("does not look like a drawing"), std::string::npos) << run.err;
  const json m = read_json(dir / "out" / "metrics.json");
  EXPECT_GT(m["plan_match"]["score"].get<double>(), 0.3);  // the right plan, held to 0.99
  EXPECT_TRUE(m["models"].empty());
  EXPECT_FALSE(fs::exists(dir / "out" / "model.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "model-gt.json"));
}

TEST(AlignCommand, BentOfficeIsFittedByTheGaussianProcesses) {
  TempDir dir;
  const json m = simulate_and_align("bent-office", 1, dir, R"(["gt", "gp", "gpgt"])");
  EXPECT_LE(m["pairs"]["error_median_m"].get<double>(), 0.08);
  const double gp = m["models"]["gp"]["mean_error_m"].get<double>();
  const double gpgt = m["models"]["gpgt"]["mean_error_m"].get<double>();
  EXPECT_LE(std::min(gp, gpgt), 0.15);
  // A 1 m bend: a global similarity cannot follow it.
  EXPECT_GT(m["models"]["gt"]["mean_error_m"].get<double>(), std::min(gp, gpgt));
}

TEST(AlignCommand, WarehouseAislesMakeNoPairsAlongThem) {
  TempDir dir;
  const json m = simulate_and_align("warehouse", 1, dir, R"(["gt"])");
  EXPECT_LE(m["pairs"]["error_median_m"].get<double>(), 0.05);
  EXPECT_LE(m["models"]["gt"]["mean_error_m"].get<double>(), 0.10);
  // Scans that see only the racks of an aisle cannot place the robot along it.
  EXPECT_GT(m["pairs"]["rejected"]["degenerate"].get<int>(), 0);
}

TEST(PairsCommand, OfficeInchesFindsTheUnitMixUp) {
  TempDir dir;
  const auto sim =
      run_floorgrid("simulate --preset office-inches --seed 1 --out " + quoted(dir / "data"));
  ASSERT_EQ(sim.status, 0) << sim.err;
  const auto run =
      run_floorgrid("pairs " + quoted(dir / "data") + " --out " + quoted(dir / "pairs.csv"));
  ASSERT_EQ(run.status, 0) << run.err;
  // The DXF header says mm, the drawing is in inches: the reader warns and reads inches, and
  // the run then finds the plan's remaining scale error.
  EXPECT_NE(run.err.find("mm"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("plan scale"), std::string::npos);
  const PlanTruth truth = io::read_plan_truth(dir / "data" / "truth.json");
  const ReferencePairs pairs = io::read_pairs_csv(dir / "pairs.csv");
  ASSERT_GT(pairs.size(), 1000);
  std::vector<double> errors;
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    errors.push_back(
        (truth.plan_to_grid(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm());
  std::nth_element(errors.begin(), errors.begin() + static_cast<long>(errors.size() / 2),
                   errors.end());
  EXPECT_LE(errors[errors.size() / 2], 0.05);
}

/// The manifest at `path` without its `key:` line.
void drop_key(const fs::path& path, const std::string& key) {
  std::string manifest = test::read_file(path);
  const std::size_t at = manifest.find("\n" + key + ":");
  ASSERT_NE(at, std::string::npos) << key;
  manifest.erase(at + 1, manifest.find('\n', at + 1) - at);
  test::write_file(path, manifest);
}

/// The value of the manifest's `key:` line, as written.
std::string key_value(const fs::path& path, const std::string& key) {
  const std::string manifest = test::read_file(path);
  const std::size_t at =
      manifest.find_first_not_of(' ', manifest.find("\n" + key + ":") + key.size() + 2);
  return manifest.substr(at, manifest.find('\n', at) - at);
}

TEST(AlignCommand, WithoutALogTheMapsAloneGiveThePairsOrSayWhyNot) {
  TempDir dir;
  ASSERT_EQ(
      run_floorgrid("simulate --preset bent-office --seed 1 --out " + quoted(dir / "data")).status,
      0);
  drop_key(dir / "data" / "dataset.yaml", "log");
  const auto run = run_floorgrid("align " + quoted(dir / "data") + " --out " + quoted(dir / "out"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const json m = read_json(dir / "out" / "metrics.json");
  EXPECT_EQ(m["pairs"]["source"], "maps");
  EXPECT_TRUE(m["maps_only"]["accepted"].get<bool>());
  EXPECT_GE(m["maps_only"]["fitness"].get<double>(), m["maps_only"]["min_fitness"].get<double>());
  EXPECT_LT(m["maps_only"]["ambiguity"].get<double>(), 0.9);
  EXPECT_GT(m["pairs"]["count"].get<int>(), 300);
  // Against the simulator's exact warp, a 1 m bend followed from the maps alone.
  const double gp = m["models"]["gp"]["mean_error_m"].get<double>();
  EXPECT_LE(gp, 0.15);
  EXPECT_LT(gp, m["models"]["gt"]["mean_error_m"].get<double>());
  const std::string report = test::read_file(dir / "out" / "report.html");
  EXPECT_NE(report.find("Alignment from the maps"), std::string::npos);
  EXPECT_EQ(report.find("from 0 scans"), std::string::npos);

  // The same gridmap on the warehouse's plan: no alignment, the fitness said, nothing written.
  ASSERT_EQ(
      run_floorgrid("simulate --preset warehouse --seed 1 --out " + quoted(dir / "other")).status,
      0);
  drop_key(dir / "other" / "dataset.yaml", "log");
  std::string manifest = test::read_file(dir / "other" / "dataset.yaml");
  const std::string gridmap = key_value(dir / "other" / "dataset.yaml", "gridmap");
  manifest.replace(manifest.find(gridmap), gridmap.size(),
                   "\"" + (dir / "data" / "gridmap.yaml").string() + "\"");
  test::write_file(dir / "other" / "dataset.yaml", manifest);
  const auto wrong =
      run_floorgrid("align " + quoted(dir / "other") + " --out " + quoted(dir / "wrong"));
  EXPECT_NE(wrong.status, 0) << wrong.out;
  EXPECT_NE(wrong.err.find("no alignment found from the maps alone"), std::string::npos)
      << wrong.err;
  EXPECT_NE(wrong.err.find("fitness"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(dir / "wrong" / "model.json"));
}

TEST(AlignCommand, BadInputExitsWithTwoAndWritesNothing) {
  TempDir dir;
  const auto missing =
      run_floorgrid("align " + quoted(dir / "nothing") + " --out " + quoted(dir / "out"));
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("nothing"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir / "out")) << "the output folder made for a failed job stays";
  // An output folder that was there before stays, even empty.
  fs::create_directories(dir / "kept");
  EXPECT_EQ(
      run_floorgrid("align " + quoted(dir / "nothing") + " --out " + quoted(dir / "kept")).status,
      2);
  EXPECT_TRUE(fs::is_directory(dir / "kept"));
  // A dataset without a log cannot make pairs: the message names the key.
  const auto sim = run_floorgrid("simulate --preset office --seed 2 --out " + quoted(dir / "data"));
  ASSERT_EQ(sim.status, 0) << sim.err;
  std::string manifest = test::read_file(dir / "data" / "dataset.yaml");
  manifest.erase(manifest.find("log:"),
                 manifest.find('\n', manifest.find("log:")) - manifest.find("log:") + 1);
  test::write_file(dir / "data" / "dataset.yaml", manifest);
  const auto no_log =
      run_floorgrid("pairs " + quoted(dir / "data") + " --out " + quoted(dir / "pairs.csv"));
  EXPECT_EQ(no_log.status, 2);
  EXPECT_NE(no_log.err.find("log"), std::string::npos) << no_log.err;
  EXPECT_FALSE(fs::exists(dir / "pairs.csv"));
  const auto bad_cv =
      run_floorgrid("align " + quoted(dir / "data") + " --out " + quoted(dir / "out") + " --cv 1");
  EXPECT_EQ(bad_cv.status, 2);
}

}  // namespace
}  // namespace floorgrid
