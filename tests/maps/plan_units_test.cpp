#include "floorgrid/maps/plan_units.hpp"

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
  EXPECT_TRUE(cm.warnings.empty());
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
  EXPECT_TRUE(warns(c, "overridden"));
  EXPECT_TRUE(warns(c, "outside"));
}

TEST(PlanUnits, HeaderOutsideOurUnitsIsReportedAndIgnored) {
  const PlanUnitChoice c = choose_plan_unit(evidence(40, 25, {}, 7), std::nullopt);  // km
  EXPECT_EQ(c.unit, PlanUnit::m);
  EXPECT_NE(c.reason.find("says km"), std::string::npos);
  EXPECT_TRUE(warns(c, "says km"));
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
