#include "floorgrid/maps/plan_unit_choice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "floorgrid/core/error.hpp"

namespace floorgrid {
namespace {

constexpr double kQuarter = std::numbers::pi / 2.0;

PlanUnitEvidence evidence(double width, double height, std::vector<PlanArc> arcs = {},
                          std::optional<int> insunits = std::nullopt) {
  PlanUnitEvidence e;
  e.extent =
      Eigen::AlignedBox2d(Eigen::Vector2d(-3.0, 7.0), Eigen::Vector2d(-3.0 + width, 7.0 + height));
  e.arcs = std::move(arcs);
  if (insunits) {
    e.header_name = insunits_name(*insunits);
    e.header_unit = plan_unit_from_insunits(*insunits);
  }
  return e;
}

std::vector<PlanArc> doors(std::size_t n, double radius, double sweep = kQuarter) {
  return std::vector<PlanArc>(n, PlanArc{radius, sweep});
}

/// Door swings drawn with their leaf.
std::vector<PlanArc> swings(std::size_t n, double radius) {
  return std::vector<PlanArc>(n, PlanArc{radius, kQuarter, true});
}

/// Double-line walls `thickness` thick with rooms `spacing` wide beyond them (drawing units).
WallBandSummary walls(double thickness, double spacing) {
  return {.faces = 200, .thickness = thickness, .thickness_share = 0.6, .spacing = spacing};
}

double probability_of(const PlanUnitChoice& c, PlanUnit unit) {
  for (const PlanUnitCandidate& candidate : c.candidates) {
    if (candidate.unit == unit) {
      return candidate.probability;
    }
  }
  return 0.0;
}

bool warns(const PlanUnitChoice& c, const std::string& text) {
  return std::any_of(c.warnings.begin(), c.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != w.npos; });
}

TEST(PlanUnits, UnitFactorsNamesAndHeaderCodes) {
  EXPECT_EQ(metres_per_unit(PlanUnit::m), 1.0);
  EXPECT_EQ(metres_per_unit(PlanUnit::cm), 0.01);
  EXPECT_EQ(metres_per_unit(PlanUnit::mm), 0.001);
  EXPECT_EQ(metres_per_unit(PlanUnit::in), 0.0254);  // exact by definition (1959)
  EXPECT_EQ(metres_per_unit(PlanUnit::ft), 0.3048);
  EXPECT_EQ(plan_unit_from_name("MM"), PlanUnit::mm);
  EXPECT_EQ(plan_unit_from_name("inch"), std::nullopt);
  // $INSUNITS codes of the DXF reference.
  EXPECT_EQ(plan_unit_from_insunits(1), PlanUnit::in);
  EXPECT_EQ(plan_unit_from_insunits(2), PlanUnit::ft);
  EXPECT_EQ(plan_unit_from_insunits(4), PlanUnit::mm);
  EXPECT_EQ(plan_unit_from_insunits(5), PlanUnit::cm);
  EXPECT_EQ(plan_unit_from_insunits(6), PlanUnit::m);
  EXPECT_EQ(plan_unit_from_insunits(0), std::nullopt);
  EXPECT_EQ(plan_unit_from_insunits(7), std::nullopt);
  EXPECT_EQ(insunits_name(0), "none");
  EXPECT_EQ(insunits_name(7), "km");
  EXPECT_EQ(insunits_name(99), "code 99");
  EXPECT_EQ(insunits_code("mm"), 4);
  EXPECT_EQ(insunits_code("none"), 0);
  EXPECT_EQ(insunits_code("km"), std::nullopt);
}

TEST(PlanUnits, UnitsOptionIsAutoOrAUnitElseAnErrorNamingTheField) {
  EXPECT_EQ(parse_units_option("auto", "units"), std::nullopt);
  EXPECT_EQ(parse_units_option("ft", "units"), PlanUnit::ft);
  try {
    parse_units_option("furlong", "floorplan_units");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "floorplan_units");
    EXPECT_NE(e.message().find("furlong"), std::string::npos);
  }
}

TEST(PlanUnits, PlausibleHeaderIsKeptWithoutWarnings) {
  // 14 x 9 m in millimetres with 900 mm doors.
  const PlanUnitChoice c = choose_plan_unit(evidence(14000, 9000, doors(5, 900), 4), std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::mm);
  EXPECT_EQ(c.metres_per_unit, 0.001);
  EXPECT_TRUE(c.warnings.empty());
  EXPECT_NE(c.reason.find("plausible"), std::string::npos);
}

TEST(PlanUnits, LyingHeaderIsOverruledByExtentAndDoorsWithAWarning) {
  // The house plan: 866 x 572 units, 36-inch doors, header says mm (0.87 m: a doll's house).
  const PlanUnitChoice c = choose_plan_unit(evidence(866, 572, doors(10, 36), 4), std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::in);
  EXPECT_TRUE(warns(c, "says mm"));
  EXPECT_TRUE(warns(c, "reads as in"));
}

TEST(PlanUnits, PlausibleSpanButWrongDoorsStillOverrulesTheHeader) {
  // In cm the drawing would span 8.7 m (plausible) but the 36-unit doors would be 0.36 m wide.
  const PlanUnitChoice c = choose_plan_unit(evidence(866, 572, doors(10, 36), 5), std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::in);
  EXPECT_TRUE(warns(c, "says cm"));
}

TEST(PlanUnits, DoorsDecideWithoutAHeaderAndOnlyQuarterTurnsCount) {
  // 800 units: cm (8 m), in (20 m) and ft (244 m) all span plausibly; 0.9 m doors say cm.
  const PlanUnitChoice cm = choose_plan_unit(evidence(800, 600, doors(4, 90)), std::nullopt);
  EXPECT_EQ(cm.unit, PlanUnit::cm);
  // Without a header the units are a guess, and always said to be one.
  EXPECT_EQ(cm.source, UnitSource::guessed);
  ASSERT_EQ(cm.warnings.size(), 1u);
  EXPECT_TRUE(warns(cm, "no $INSUNITS: the units were guessed as cm"));
  // The same radii on half-circle arcs are not door swings: the typical size decides.
  const PlanUnitChoice typical =
      choose_plan_unit(evidence(800, 600, doors(4, 90, std::numbers::pi)), std::nullopt);
  EXPECT_EQ(typical.unit, PlanUnit::in);  // 20 m is nearest the 50 m middle of 5..500 m
  EXPECT_TRUE(warns(typical, "ambiguous"));
}

TEST(PlanUnits, MetresSiteWithoutHeaderIsMetresButAmbiguousWithFeet) {
  const PlanUnitChoice c = choose_plan_unit(evidence(43.1, 32.6), std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::m);  // 43 m rather than 13 m in feet
  EXPECT_TRUE(warns(c, "ft"));
  EXPECT_NE(c.reason.find("no $INSUNITS"), std::string::npos);
}

TEST(PlanUnits, ExplicitUnitIsObeyedEvenWhenImplausible) {
  const PlanUnitChoice c = choose_plan_unit(evidence(14000, 9000, doors(5, 900), 4), PlanUnit::m);
  EXPECT_EQ(c.unit, PlanUnit::m);
  EXPECT_NE(c.reason.find("requested"), std::string::npos);
  EXPECT_EQ(c.source, UnitSource::requested);
  EXPECT_EQ(c.candidates.front().unit, PlanUnit::mm);  // what the drawing says nonetheless
  EXPECT_TRUE(warns(c, "overridden"));
  EXPECT_TRUE(warns(c, "outside"));
}

TEST(PlanUnits, HeaderOutsideOurUnitsIsReportedAndIgnored) {
  const PlanUnitChoice c = choose_plan_unit(evidence(40, 25, {}, 7), std::nullopt);  // km
  EXPECT_EQ(c.unit, PlanUnit::m);
  EXPECT_NE(c.reason.find("says km"), std::string::npos);
  EXPECT_TRUE(warns(c, "says km"));
}

TEST(PlanUnits, FourDoorSwingsDoNotOverruleAPlausibleHeaderButAreReported) {
  // A 95 x 59 m building in cm whose only door swings are four 36-unit ones (an inch door block
  // inserted unscaled): 0.36 m in cm, 0.91 m in inches. The walls and rooms are a cm building's.
  PlanUnitEvidence e = evidence(9500, 5900, swings(4, 36), 5);
  e.walls = walls(12, 588);
  const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::cm);
  EXPECT_EQ(c.source, UnitSource::header);
  EXPECT_NE(c.confidence, UnitConfidence::high);  // the doors disagree
  EXPECT_TRUE(warns(c, "the 4 door swings would be 0.36 m wide"));
  EXPECT_TRUE(warns(c, "as if it were drawn in inches"));
  EXPECT_GT(probability_of(c, PlanUnit::cm), probability_of(c, PlanUnit::in));
  EXPECT_GT(probability_of(c, PlanUnit::in), 0.01);  // still a candidate for the robot to test
}

TEST(PlanUnits, ManyDoorSwingsOverruleAPlausibleHeader) {
  // 2362 x 1181 units is a plausible 23.6 x 11.8 m in cm, but its 12 door swings of 36 units,
  // 4.5-unit walls and 200-unit rooms are a house's in inches.
  PlanUnitEvidence e = evidence(2362, 1181, swings(12, 36), 5);
  e.walls = walls(4.5, 200);
  const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::in);
  EXPECT_EQ(c.source, UnitSource::header_overruled);
  EXPECT_EQ(c.confidence, UnitConfidence::high);
  EXPECT_TRUE(warns(c, "$INSUNITS says cm but the drawing reads as in"));
  EXPECT_TRUE(warns(c, "12 door swings 0.914 m wide"));
  EXPECT_TRUE(warns(c, "in centimetres the 12 door swings would be 0.36 m wide"));
}

TEST(PlanUnits, StoreysSideBySideStayInMetres) {
  // Four 130 x 40 m storeys side by side: 565 m, more than a storey, in metres.
  for (const std::optional<int> header : {std::optional<int>(6), std::optional<int>()}) {
    PlanUnitEvidence e = evidence(565, 40, swings(40, 0.9), header);
    e.walls = walls(0.12, 6.4);
    const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
    EXPECT_EQ(c.unit, PlanUnit::m);
    EXPECT_EQ(c.confidence, UnitConfidence::high);
    EXPECT_EQ(c.source, header ? UnitSource::header : UnitSource::guessed);
    EXPECT_EQ(c.warnings.size(), header ? 0u : 1u);
  }
  // Nor does a large extent alone move a header: without features it is kept, less surely.
  const PlanUnitChoice bare = choose_plan_unit(evidence(2000, 300, {}, 6), std::nullopt);
  EXPECT_EQ(bare.unit, PlanUnit::m);
  EXPECT_EQ(bare.source, UnitSource::header);
  EXPECT_EQ(bare.confidence, UnitConfidence::medium);
  EXPECT_TRUE(bare.warnings.empty());
}

TEST(PlanUnits, WallsAndRoomsDecideWithoutDoors) {
  // 565 x 40 units: metres (565 m) or feet (172 m) by extent; 0.12-unit walls with 6.4-unit
  // rooms are a building's in metres, 3.7 cm walls in feet.
  PlanUnitEvidence e = evidence(565, 40);
  e.walls = walls(0.12, 6.4);
  const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::m);
  EXPECT_GT(probability_of(c, PlanUnit::m), 0.8);
  EXPECT_NE(c.reason.find("walls 0.12 m thick"), std::string::npos) << c.reason;
}

TEST(PlanUnits, DimensionTextsDecide) {
  // 800 x 600 units is plausible in cm, inches and feet; texts stating feet and inches for the
  // measured lengths say inches.
  PlanUnitEvidence e = evidence(800, 600);
  e.dimensions = {{150.0, 150 * 0.0254, "12'-6\""},
                  {37.0, 37 * 0.0254, "3'-1\""},
                  {192.0, 192 * 0.0254, "16'-0\""}};
  const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::in);
  EXPECT_NE(c.reason.find("3 of 3 dimension texts fit (12'-6\" for 150 units)"), std::string::npos)
      << c.reason;
}

TEST(PlanUnits, FarOffStraysDoNotStretchTheExtent) {
  // A campus of 340 x 206 m in metres at UTM coordinates with a marker left at the origin:
  // the whole extent (455 x 5650 km) is absurd in metres, the core extent is not.
  PlanUnitEvidence e = evidence(455340, 5650206, swings(150, 1.0));
  e.core_extent =
      Eigen::AlignedBox2d(Eigen::Vector2d(455000, 5650000), Eigen::Vector2d(455340, 5650206));
  e.walls = walls(0.15, 7.4);
  const PlanUnitChoice c = choose_plan_unit(e, std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::m);
  EXPECT_EQ(c.source, UnitSource::guessed);
  EXPECT_TRUE(warns(c, "guessed as m"));
  EXPECT_FALSE(warns(c, "implausible"));
}

TEST(PlanUnits, CandidatesArePlausibleUnitsMostProbableFirst) {
  const PlanUnitChoice c =
      choose_plan_unit(evidence(800, 600, doors(4, 90, std::numbers::pi)), std::nullopt);
  ASSERT_GE(c.candidates.size(), 2u);
  EXPECT_EQ(c.candidates.front().unit, c.unit);
  double sum = 0.0;
  for (std::size_t i = 0; i < c.candidates.size(); ++i) {
    EXPECT_GE(c.candidates[i].probability, 0.01);
    if (i > 0) {
      EXPECT_LE(c.candidates[i].probability, c.candidates[i - 1].probability);
      EXPECT_LE(c.candidates[i].score, c.candidates[i - 1].score);
    }
    sum += c.candidates[i].probability;
  }
  EXPECT_LE(sum, 1.0 + 1e-12);
  EXPECT_EQ(c.confidence, UnitConfidence::low);
  EXPECT_FALSE(c.evidence.empty());
  EXPECT_EQ(to_string(c.confidence), "low");
  EXPECT_EQ(to_string(UnitSource::header_overruled), "header_overruled");
}

TEST(PlanUnits, ImplausibleInEveryUnitPicksTheClosestAndWarns) {
  const PlanUnitChoice c = choose_plan_unit(evidence(5e7, 1e7), std::nullopt);
  EXPECT_EQ(c.unit, PlanUnit::mm);  // 50 km, the least absurd
  EXPECT_TRUE(warns(c, "implausible in every unit"));
}

TEST(PlanUnits, EmptyDrawingFallsBackToHeaderOrMetres) {
  PlanUnitEvidence none;
  EXPECT_EQ(choose_plan_unit(none, std::nullopt).unit, PlanUnit::m);
  none.header_unit = PlanUnit::ft;
  none.header_name = "ft";
  EXPECT_EQ(choose_plan_unit(none, std::nullopt).unit, PlanUnit::ft);
}

}  // namespace
}  // namespace floorgrid
