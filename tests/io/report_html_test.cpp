// report.html from an output folder: self-contained (no network, pictures as data URLs), every
// string from the data escaped, the numbers those of metrics.json as report_format writes them,
// heat maps picked up when present, and a folder without the optional files still reported.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/base64.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/report/report_format.hpp"
#include "floorgrid/io/report/report_html.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

/// A small align result: two models with a truth, gt chosen, a hostile dataset name.
json small_metrics() {
  json histogram = json::array();
  for (int i = 0; i < 21; ++i)
    histogram.push_back(i < 3 ? 100 - 30 * i : 0);
  return {{"format", "floorgrid-metrics"},
          {"version", 1},
          {"dataset", "<script>alert(\"x\")</script> & co"},
          {"chosen_model", "gt"},
          {"pairs",
           {{"count", 12345},
            {"scans", 40},
            {"converged_fraction", 0.875},
            {"converged_periods", 2},
            {"error_median_m", 0.0312},
            {"error_mean_m", 0.041},
            {"error_p95_m", 0.12},
            {"noise_rms_m", 0.02},
            {"wall_slide",
             {{"applied", true},
              {"iterations", 2},
              {"pairs_on_walls", 9876},
              {"noise_along_m", 0.081},
              {"noise_across_m", 0.037},
              {"median_slide_m", 0.04},
              {"p95_slide_m", 0.2},
              {"localized_error_median_m", 0.059}}},
            {"rejected", {{"not_converged", 321}, {"off_plan_wall", 4567}}}}},
          {"plan_scale", 1.02134},
          {"plan_scale_std", 0.00012},
          {"plan_scale_estimated", true},
          {"domain", {{"kind", "warp"}, {"points", 2500}}},
          {"localization",
           {{"grid_start_scan", 3},
            {"plan_start_scan", 5},
            {"longest_gap_scans", 7},
            {"notes", {"a note with <b>markup</b>"}}}},
          {"models",
           {{"gt",
             {{"mean_error_m", 0.0421},
              {"median_error_m", 0.0333},
              {"p95_error_m", 0.1188},
              {"cv_error_m", 0.0567},
              {"cv_kind", "blocked"},
              {"fit_seconds", 0.061},
              {"pairs_used", 12345},
              {"error_histogram", histogram},
              {"wall_distance_median_m", 0.05},
              {"back_and_forth",
               {{"min_m", 0.0},
                {"mean_m", 1.2e-13},
                {"max_m", 3.8e-13},
                {"points", 2500},
                {"not_invertible", 0}}}}},
            {"tps",
             {{"mean_error_m", 0.0612},
              {"median_error_m", 0.0444},
              {"p95_error_m", 0.2},
              {"cv_error_m", 0.07},
              {"fit_seconds", 0.24},
              {"error_histogram", histogram},
              {"back_and_forth", {{"min_m", 0.0}, {"mean_m", 1e-9}, {"max_m", 2e-9}}}}},
            {"ct", {{"failure", "too few pairs <here>"}}}}},
          {"timings_s",
           {{"load", 0.5}, {"localize", 12.25}, {"fit", 3.0}, {"evaluate", 1.5}, {"write", 0.2}}}};
}

const char* kScansCsv =
    "scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,plan_scale,grid_x,"
    "grid_y,grid_theta,grid_state,grid_converged,grid_fit,grid_scale,consistent,pairs\n"
    "0,1.0,0,0,0,global,0,,1,0,0,0,global,0,,1,1,0\n"
    "1,1.1,0,0,0,tracking,1,0.8,1,0,0,0,tracking,1,0.9,1,1,40\n"
    "2,1.2,0,0,0,tracking,1,0.8,1,0,0,0,tracking,1,0.9,1,1,38\n";

/// An output folder holding `metrics` and, when `full`, scans.csv, an overlay and a heat map.
void write_folder(const fs::path& folder, const json& metrics, bool full) {
  test::write_file(folder / "metrics.json", metrics.dump(1));
  if (!full)
    return;
  test::write_file(folder / "scans.csv", kScansCsv);
  fs::create_directories(folder / "overlays");
  fs::create_directories(folder / "heatmaps");
  io::write_png_rgb(folder / "overlays" / "overlay-gt.png", 2, 1, {255, 0, 0, 0, 255, 0});
  io::write_png(folder / "heatmaps" / "heat-gt.png", 1, 1, {128});
}

TEST(ReportHtml, NumbersAreMetricsJsonsAsTheReportFormatsThem) {
  TempDir dir;
  const json m = small_metrics();
  write_folder(dir.path(), m, true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  const json& gt = m["models"]["gt"];
  for (const std::string& expected :
       {io::format_metres(gt["mean_error_m"]), io::format_metres(gt["median_error_m"]),
        io::format_metres(gt["p95_error_m"]), io::format_metres(gt["cv_error_m"]),
        io::format_metres(m["models"]["tps"]["mean_error_m"]),
        io::format_metres(gt["back_and_forth"]["max_m"]), io::format_count(m["pairs"]["count"]),
        io::format_count(m["pairs"]["rejected"]["off_plan_wall"]),
        io::format_percent(m["pairs"]["converged_fraction"]), io::format_ratio(m["plan_scale"]),
        io::format_ratio(m["plan_scale_std"]), io::format_seconds(m["timings_s"]["localize"]),
        io::format_metres(m["pairs"]["error_median_m"]),
        io::format_count(m["pairs"]["wall_slide"]["pairs_on_walls"]),
        io::format_metres(m["pairs"]["wall_slide"]["noise_along_m"]),
        io::format_metres(m["pairs"]["wall_slide"]["localized_error_median_m"])}) {
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  }
  // The formats themselves: units, and tiny drifts by magnitude.
  EXPECT_EQ(io::format_metres(0.0421), "0.042 m");
  EXPECT_EQ(io::format_metres(3.8e-13), "3.8e-13 m");
  EXPECT_EQ(io::format_percent(json(0.875)), "87.5%");
  EXPECT_EQ(io::format_count(12345), "12\u202f345");
  EXPECT_EQ(io::format_ratio(json(1.02134)), "1.0213");
  EXPECT_EQ(io::format_seconds(12.25), "12.2 s");
  EXPECT_EQ(io::format_metres(json(nullptr)), "n/a");
}

TEST(ReportHtml, IsSelfContainedAndEscapesTheData) {
  TempDir dir;
  write_folder(dir.path(), small_metrics(), true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  // Every src= is a data: URL; no stylesheet or script is linked.
  const std::regex src(R"(src\s*=\s*["']?([^"'\s>]*))");
  int sources = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator();
       ++it, ++sources) {
    EXPECT_EQ((*it)[1].str().rfind("data:", 0), 0u) << (*it)[0].str();
  }
  EXPECT_EQ(sources, 2);  // the overlay and the heat map
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  // No address but the credited chart library's (its own banner and the footer's credit).
  const std::regex address(R"(https?://[^\s"'<>)]*)");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), address);
       it != std::sregex_iterator(); ++it) {
    EXPECT_EQ((*it)[0].str(), "https://github.com/leeoniya/uPlot") << (*it)[0].str();
  }
  EXPECT_NE(html.find("uPlot (MIT License"), std::string::npos);
  // The data's strings are text, never markup.
  EXPECT_EQ(html.find("<script>alert"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; co"),
            std::string::npos);
  EXPECT_NE(html.find("a note with &lt;b&gt;markup&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("too few pairs &lt;here&gt;"), std::string::npos);
  // The chart data cannot end its <script> element early.
  const std::size_t data = html.find("id=\"report-data\">");
  ASSERT_NE(data, std::string::npos);
  EXPECT_EQ(html.substr(data, html.find("</script>", data) - data).find("</"), std::string::npos);
}

TEST(ReportHtml, PicksUpHeatMapsAndOverlays) {
  TempDir dir;
  write_folder(dir.path(), small_metrics(), true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  const std::string heat = io::base64_encode(test::read_file(dir / "heatmaps/heat-gt.png"));
  EXPECT_NE(html.find("data:image/png;base64," + heat), std::string::npos);
  EXPECT_NE(html.find("error against the truth, gt"), std::string::npos);
  EXPECT_NE(html.find("id=\"chart-localization\""), std::string::npos);
  EXPECT_EQ(html.find("No heat maps in this folder"), std::string::npos);
}

TEST(ReportHtml, AFolderWithOnlyMetricsIsReportedAndWithoutMetricsRefused) {
  TempDir dir;
  write_folder(dir.path(), small_metrics(), false);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(html.find("No heat maps in this folder"), std::string::npos);
  EXPECT_NE(html.find("No scans.csv in this folder"), std::string::npos);
  TempDir empty;
  EXPECT_THROW(io::write_report_html(empty.path()), InputError);
  EXPECT_FALSE(fs::exists(empty / "report.html"));
}

/// small_metrics() as a maps-only alignment wrote it: no scans, pairs from the maps, maps_only.
json maps_only_metrics(bool accepted) {
  json m = small_metrics();
  m["pairs"] = {{"count", 1397}, {"scans", 0}, {"source", "maps"}};
  m["maps_only"] = {{"accepted", accepted},
                    {"fitness", 0.4567},
                    {"min_fitness", 0.2},
                    {"min_on_walls", 0.4},
                    {"ambiguity", 0.31},
                    {"max_ambiguity", 0.9},
                    {"on_walls", 0.548},
                    {"in_free_space", 0.088},
                    {"pairs", 1397},
                    {"points", 4838},
                    {"stages", 3},
                    {"median_distance_m", 0.0621},
                    {"diagnosis", accepted ? "" : "another <place> fits as well"},
                    {"seconds", 8.38},
                    {"registration",
                     {{"scale", 0.8279},
                      {"theta_deg", 267.04},
                      {"score", 0.18},
                      {"on_walls", 0.356},
                      {"in_free_space", 0.177},
                      {"runner_up_score", 0.09},
                      {"correlation", true},
                      {"seconds", 8.29}}}};
  return m;
}

TEST(ReportHtml, AMapsOnlyAlignmentShowsItsRegistrationBendingAndFitness) {
  TempDir dir;
  const json m = maps_only_metrics(true);
  write_folder(dir.path(), m, false);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  // Its own section instead of the filters' story, and no "from 0 scans".
  EXPECT_NE(html.find("Alignment from the maps"), std::string::npos);
  EXPECT_EQ(html.find("from 0 scans"), std::string::npos);
  EXPECT_EQ(html.find("Both filters converged"), std::string::npos);
  for (const std::string& expected :
       {io::format_count(m["maps_only"]["points"]), io::format_count(m["pairs"]["count"]),
        io::format_metres(m["maps_only"]["median_distance_m"]),
        io::format_percent(m["maps_only"]["on_walls"]), io::format_ratio(json(1.0 / 0.8279)),
        std::string("267.0&deg;"), std::string("<b>0.46</b>, at least 0.20 needed"),
        std::string("(at least 0.40 needed)"), std::string("Ambiguity 0.31 (below 0.90 needed)"),
        std::string("estimated from the maps")})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  EXPECT_EQ(html.find("ot accepted"), std::string::npos);

  // Not accepted: said as a warning, with the diagnosis escaped.
  TempDir rejected;
  write_folder(rejected.path(), maps_only_metrics(false), false);
  const std::string warning = test::read_file(io::write_report_html(rejected.path()));
  EXPECT_NE(warning.find("Not accepted: another &lt;place&gt; fits as well"), std::string::npos);
  EXPECT_NE(warning.find("<b>not accepted</b>"), std::string::npos);
}

TEST(ReportHtml, ARunWithTheMapsPairsAddedShowsBoth) {
  TempDir dir;
  json m = maps_only_metrics(true);
  m["pairs"] = small_metrics()["pairs"];
  m["pairs"]["source"] = "both";
  write_folder(dir.path(), m, true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(html.find("Both filters converged"), std::string::npos);
  EXPECT_NE(html.find("<h3>Alignment from the maps</h3>"), std::string::npos);
  EXPECT_NE(html.find("and " + io::format_count(1397) + " from the maps alone"), std::string::npos);
  EXPECT_NE(html.find("from " + io::format_count(40) + " scans and the maps"), std::string::npos);
}

TEST(ReportHtml, ARunFilledByTheMapsCountsOnlyTheFillAndShowsTheAgreement) {
  TempDir dir;
  json m = maps_only_metrics(true);
  m["pairs"] = small_metrics()["pairs"];
  m["pairs"]["source"] = "both";
  m["sources"] = {{"chosen", "run"},
                  {"filled_pairs", 37},
                  {"agreement",
                   {{"agree", true},
                    {"median_m", 0.12},
                    {"p90_m", 0.4},
                    {"tolerance_m", 0.5},
                    {"run_scale", 1.0213},
                    {"maps_scale", 1.0305},
                    {"scale_tolerance", 0.0412}}}};
  write_folder(dir.path(), m, true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(html.find("and " + io::format_count(37) + " from the maps alone"), std::string::npos);
  EXPECT_NE(html.find("<b>they agree</b>"), std::string::npos);
  for (const std::string& expected :
       {io::format_metres(0.12), io::format_metres(0.5), io::format_ratio(json(1.0213)),
        io::format_ratio(json(1.0305)), io::format_percent(json(0.0412 / 1.0305))})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  EXPECT_EQ(html.find("without the walls' faces"), std::string::npos);
  // A scale refitted with the walls' faces: the report gives it without them too.
  m["sources"]["agreement"]["run_scale_at_drawn_walls"] = 1.0111;
  write_folder(dir.path(), m, true);
  const std::string refitted = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(refitted.find(io::format_ratio(json(1.0111)) + " without the walls' faces"),
            std::string::npos);
  // The bias in every std_m, and what measured it; nothing said of none.
  EXPECT_EQ(refitted.find("a bias all pairs share"), std::string::npos);
  m["shared_bias"] = {
      {"std_m", 0.13}, {"from", "agreement"}, {"sources_m", 0.12}, {"faces_m", 0.05}};
  write_folder(dir.path(), m, true);
  const std::string biased = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(biased.find("a bias all pairs share, which their cross-validation cannot see: <b>" +
                        io::format_metres(0.13) + "</b>: " + io::format_metres(0.12) +
                        " from where the run's pairs and the maps' alignment lie apart"),
            std::string::npos);
  EXPECT_NE(biased.find(" and " + io::format_metres(0.05) + " for the outer walls' faces"),
            std::string::npos);
  m["shared_bias"] = {{"std_m", 0.0}, {"from", "none"}};
  write_folder(dir.path(), m, true);
  EXPECT_EQ(test::read_file(io::write_report_html(dir.path())).find("a bias all pairs share"),
            std::string::npos);
}

TEST(ReportHtml, TheMapsStandingInForAFailedRunSaySoAndWhy) {
  TempDir dir;
  json m = maps_only_metrics(true);
  m["pairs"]["fallback"] = "the run covers 4% of the gridmap walls <20%";
  write_folder(dir.path(), m, true);
  const std::string html = test::read_file(io::write_report_html(dir.path()));
  EXPECT_NE(html.find("<b>the run's were not used</b>"), std::string::npos);
  EXPECT_NE(html.find("<b>The run's pairs were not used:</b> the run covers 4% of the gridmap "
                      "walls &lt;20%."),
            std::string::npos);

  // A maps-only alignment (no run at all) says nothing of the kind.
  TempDir plain;
  write_folder(plain.path(), maps_only_metrics(true), true);
  const std::string clean = test::read_file(io::write_report_html(plain.path()));
  EXPECT_EQ(clean.find("were not used"), std::string::npos);
}

TEST(Base64, EncodesRfc4648Vectors) {
  EXPECT_EQ(io::base64_encode(""), "");
  EXPECT_EQ(io::base64_encode("f"), "Zg==");
  EXPECT_EQ(io::base64_encode("fo"), "Zm8=");
  EXPECT_EQ(io::base64_encode("foo"), "Zm9v");
  EXPECT_EQ(io::base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(io::base64_encode(std::string("\xff\x00\x10", 3)), "/wAQ");
}

}  // namespace
}  // namespace floorgrid
