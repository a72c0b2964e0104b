// Units of DXF drawings as real CAD programs write them: drawings made by ezdxf
// (tests/io/make_unit_fixtures.py, run by Debian's /usr/bin/python3) after files on which the
// units were once guessed wrong, and dimension texts as unit evidence in hand-written DXF.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

bool has_warning(const io::DxfReport& report, const std::string& text) {
  return std::any_of(report.warnings.begin(), report.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != w.npos; });
}

double probability_of(const io::DxfReport& report, PlanUnit unit) {
  for (const PlanUnitCandidate& c : report.unit_candidates) {
    if (c.unit == unit) {
      return c.probability;
    }
  }
  return 0.0;
}

std::string all_of(const io::DxfReport& report) {
  std::string out = report.units_reason + "\n";
  for (const std::string& w : report.warnings) {
    out += "warning: " + w + "\n";
  }
  for (const std::string& e : report.units_evidence) {
    out += "evidence: " + e + "\n";
  }
  return out;
}

/// The drawings, written once for the suite.
class DxfUnits : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!ezdxf_available()) {
      return;
    }
    folder_ = std::make_unique<TempDir>();
    const CommandResult made =
        run_command("/usr/bin/python3 '" FLOORGRID_SOURCE_DIR "/tests/io/make_unit_fixtures.py' " +
                    quoted(folder_->path()));
    ASSERT_EQ(made.status, 0) << made.err;
  }
  static void TearDownTestSuite() { folder_.reset(); }

  void SetUp() override { FLOORGRID_REQUIRE_EZDXF(); }

  static io::DxfReport read(const std::string& name) {
    return io::read_dxf(folder_->path() / name).report;
  }

  static std::unique_ptr<TempDir> folder_;
};

std::unique_ptr<TempDir> DxfUnits::folder_;

TEST_F(DxfUnits, CentimetreHeaderIsKeptAgainstFourInchSizedDoorSwings) {
  // Was read as inches (241 x 150 m) on the evidence of its four door arcs alone.
  const io::DxfReport r = read("cm_header_four_doors.dxf");
  EXPECT_EQ(r.header_units, "cm");
  EXPECT_EQ(r.units_used, "cm") << all_of(r);
  EXPECT_EQ(r.units_source, "header");
  EXPECT_EQ(r.units_confidence, "medium");
  EXPECT_NEAR(r.extent_m.sizes().x(), 95.0, 1e-6);
  // The disagreement is reported with how many arcs and what they imply.
  EXPECT_TRUE(has_warning(r, "the 4 door swings would be 0.36 m wide")) << all_of(r);
  EXPECT_TRUE(has_warning(r, "as if it were drawn in inches"));
  EXPECT_GT(probability_of(r, PlanUnit::in), 0.01);
  EXPECT_GT(probability_of(r, PlanUnit::cm), probability_of(r, PlanUnit::in));
}

TEST_F(DxfUnits, StoreysSideBySideStayInMetresWithOrWithoutHeader) {
  // 565 m wide in all: was read as feet.
  const io::DxfReport m = read("storeys_side_by_side_m.dxf");
  EXPECT_EQ(m.units_used, "m") << all_of(m);
  EXPECT_EQ(m.units_source, "header");
  EXPECT_EQ(m.units_confidence, "high");
  EXPECT_TRUE(m.warnings.empty()) << all_of(m);
  EXPECT_NEAR(m.extent_m.sizes().x(), 565.0, 1e-6);

  const io::DxfReport none = read("storeys_side_by_side_none.dxf");
  EXPECT_EQ(none.header_units, "none");
  EXPECT_EQ(none.units_used, "m") << all_of(none);
  EXPECT_EQ(none.units_source, "guessed");
  EXPECT_TRUE(has_warning(none, "no $INSUNITS: the units were guessed as m"));
}

TEST_F(DxfUnits, UnitlessCampusInMetresIsMetresWithAWarning) {
  // 340 x 206 m at UTM coordinates with a marker at the origin: was read as mm (5.7 km).
  const io::DxfReport r = read("campus_unitless_m.dxf");
  EXPECT_EQ(r.units_used, "m") << all_of(r);
  EXPECT_EQ(r.units_source, "guessed");
  EXPECT_EQ(r.units_confidence, "high");
  EXPECT_TRUE(has_warning(r, "no $INSUNITS: the units were guessed as m")) << all_of(r);
  EXPECT_FALSE(has_warning(r, "implausible"));
  EXPECT_NE(r.units_evidence[0].find("340 m x 206 m in metres"), std::string::npos) << all_of(r);
}

TEST_F(DxfUnits, UnitlessMillimetreDrawingIsMillimetresWithAWarning) {
  // Was read as mm without a word.
  const io::DxfReport r = read("unitless_mm_doors.dxf");
  EXPECT_EQ(r.units_used, "mm") << all_of(r);
  EXPECT_EQ(r.units_source, "guessed");
  EXPECT_TRUE(has_warning(r, "the units were guessed as mm"));
  EXPECT_NE(r.units_reason.find("door swings 0.9 m wide"), std::string::npos) << all_of(r);
  EXPECT_NEAR(r.extent_m.sizes().x(), 30.0, 1e-9);
}

TEST_F(DxfUnits, LyingHeadersAreOverruledByDoorsWallsAndDimensions) {
  const io::DxfReport mm = read("header_lies_mm_inches.dxf");
  EXPECT_EQ(mm.header_units, "mm");
  EXPECT_EQ(mm.units_used, "in") << all_of(mm);
  EXPECT_EQ(mm.units_source, "header_overruled");
  EXPECT_EQ(mm.units_confidence, "high");
  EXPECT_TRUE(has_warning(mm, "$INSUNITS says mm but the drawing reads as in"));
  // Both kinds of dimension text: overrides and measured values with an inch mark.
  EXPECT_NE(mm.units_reason.find("6 of 6 dimension texts fit"), std::string::npos) << all_of(mm);

  // Under a cm header the inch drawing would be a plausible 23.6 m: its doors decide.
  const io::DxfReport cm = read("header_lies_cm_inches.dxf");
  EXPECT_EQ(cm.units_used, "in") << all_of(cm);
  EXPECT_EQ(cm.units_source, "header_overruled");
  EXPECT_TRUE(has_warning(cm, "in centimetres the 22 door swings would be 0.36 m wide"))
      << all_of(cm);
}

TEST_F(DxfUnits, AnExplicitUnitIsObeyedAndTheDrawingsOpinionStillReported) {
  io::DxfReadOptions options;
  options.units = "ft";
  const io::DxfReport r =
      io::read_dxf(folder_->path() / "storeys_side_by_side_m.dxf", options).report;
  EXPECT_EQ(r.units_used, "ft");
  EXPECT_EQ(r.units_source, "requested");
  EXPECT_EQ(r.unit_candidates.front().unit, PlanUnit::m);
  EXPECT_TRUE(has_warning(r, "overridden by the requested ft"));
}

TEST(DxfUnitsDimensions, DimensionTextsTellInchesEvenInsideScaledBlocks) {
  TempDir dir;
  // No header, 800 x 600 units: cm, inches and feet are all plausible sizes. Dimensions say
  // 12'-6" for 150 units: one placed directly (text override, measurement 42), one in a block
  // inserted at scale 2 (measuring 75 block units, 150 drawing units), one whose text AutoCAD
  // drew into its block, and one with a malformed measurement (no evidence, no error).
  const std::string entities = R"(0 LINE
8 WALLS
10 0
20 0
11 800
21 600
0 DIMENSION
8 DIMS
2 *D1
70 32
42 150
1 12'-6"
0 INSERT
8 DIMS
2 DETAIL
10 0
20 0
41 2
42 2
0 DIMENSION
8 DIMS
2 *D2
70 33
42 150
1 <>
0 DIMENSION
8 DIMS
70 32
42 1x5
1 12'-6")";
  const std::string blocks = R"(0 BLOCK
2 DETAIL
70 0
10 0
20 0
0 DIMENSION
8 0
70 32
42 75
1 12'-6"
0 ENDBLK
0 BLOCK
2 *D2
70 1
10 0
20 0
0 MTEXT
8 0
1 \A1;12'-6"
0 ENDBLK)";
  const auto path = put(dir, dxf_file(entities, blocks));
  const io::DxfFloorplan read = io::read_dxf(path);
  EXPECT_EQ(read.report.units_used, "in") << all_of(read.report);
  EXPECT_NE(read.report.units_reason.find("3 of 3 dimension texts fit (12'-6\" for 150 units)"),
            std::string::npos)
      << all_of(read.report);
  EXPECT_EQ(read.report.annotation_skipped.at("DIMENSION"), 4u);
}

}  // namespace
}  // namespace floorgrid::test
