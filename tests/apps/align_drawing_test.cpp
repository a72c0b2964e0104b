// `floorgrid align` on a dataset built from an architect's drawing (simulate --from-plan): the
// laser meets the outer walls at their inner faces, so the gridmap's outline registers on the
// drawn one small, and the run must not keep that scale; and a pass tracked again that matched
// far fewer scans must not replace the one before.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

using nlohmann::json;
using test::quoted;
using test::read_json;
using test::run_floorgrid;
using test::TempDir;

bool has_note(const json& metrics, const std::string& text) {
  for (const json& note : metrics["localization"]["notes"])
    if (note.get<std::string>().find(text) != std::string::npos)
      return true;
  return false;
}

/// `simulate --from-plan` of a drawing in ../shared/data (with `args`), then `align` with gt
/// only (the pairs do not depend on the models); the alignment's metrics.json.
json simulate_and_align(const TempDir& dir, const std::string& drawing, const std::string& args) {
  const auto sim = run_floorgrid("simulate --from-plan " + quoted(test::data_path(drawing)) + " " +
                                 args + " --out " + quoted(dir / "data"));
  EXPECT_EQ(sim.status, 0) << sim.err;
  test::write_file(dir / "gt.yaml", "align:\n  models:\n    models: gt\n");
  const auto run = run_floorgrid("align " + quoted(dir / "data") + " --config " +
                                 quoted(dir / "gt.yaml") + " --out " + quoted(dir / "out"));
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  return read_json(dir / "out" / "metrics.json");
}

TEST(AlignOnADrawing, TheRunRaisesTheScaleTheMapsRegisteredSmall) {
  // bench/real_matrix.sh's F5 row at seed 5: the Halmstad F5 layout's walls are thin strokes,
  // built into outer walls of 0.3-0.45 m; the maps' faces fit finds its two offsets alike and
  // is not used, and the run's surface shift is under a pixel.
  FLOORGRID_REQUIRE_DATA("halmstad/F5/layout/F5_layout.png");
  TempDir dir;
  const json m = simulate_and_align(dir, "halmstad/F5/layout/F5_layout.png",
                                    "--resolution 0.05 --seed 5 --drawing-errors some");
  ASSERT_FALSE(HasFailure());
  const double truth = m["domain"]["truth_plan_scale"].get<double>();
  // The maps' registration, which the run used to keep, is 0.6% small here (its similarity
  // maps the gridmap into the plan: plan metres per world metre).
  const double registered = 1.0 / m["maps_only"]["registration"]["scale"].get<double>();
  EXPECT_LT(100.0 * (registered / truth - 1.0), -0.4);
  // Refitted alone on the run's scans, the scale comes out higher, and is used: within the
  // issue's 0.15% of the truth (measured -0.01%). With raise_registered_scale: false the run
  // keeps the registered scale and the pairs are as before (bench/real_matrix.sh's rows).
  EXPECT_TRUE(has_note(m, "the refit is used"));
  EXPECT_FALSE(has_note(m, "the plan scale is kept as the maps' registration gave it"));
  EXPECT_LT(std::abs(100.0 * (m["plan_scale"].get<double>() / truth - 1.0)), 0.15);
}

TEST(AlignOnADrawing, APassTrackedAgainThatMatchesFarFewerScansIsNotKept) {
  // bench/real_matrix.sh's house row at seed 3 (a DXF drawing): the first pass's refit moves
  // the scale, and the plan filter, tracked again at it, matches 23 scans where it had matched
  // 360; their refit put the scale 8.9% off. The pass before is kept
  // (ScaleRefitOptions::retrack_min_share), and its scale is right.
  FLOORGRID_REQUIRE_DATA("dxf/house_floorplan_r2004.dxf");
  TempDir dir;
  const json m =
      simulate_and_align(dir, "dxf/house_floorplan_r2004.dxf", "--seed 3 --drawing-errors some");
  ASSERT_FALSE(HasFailure());
  EXPECT_TRUE(has_note(m, "the last pass's poses and scale kept"));
  const double truth = m["domain"]["truth_plan_scale"].get<double>();
  EXPECT_LT(std::abs(m["plan_scale"].get<double>() / truth - 1.0), 0.005);  // measured 0.01%
}

}  // namespace
}  // namespace floorgrid
