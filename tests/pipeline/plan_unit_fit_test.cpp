// The robot's map deciding between the units a drawing may be in, against the simulator's
// plan whose true size is known.
#include "floorgrid/pipeline/plan_unit_fit.hpp"

#include <gtest/gtest.h>

#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/simulation/simulator.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

const SimulatedDataset& office() {
  static const SimulatedDataset d = simulate("office", 2);
  return d;
}

// The office's walls in metres as a reader would have them when it took the drawing's unit
// for `read_as` while the coordinates are in `drawn_in`; `size` draws the plan that many times
// its true size first.
VectorFloorplan read_plan(PlanUnit drawn_in, PlanUnit read_as, double size = 1.0) {
  return filter_layers(office().plan, {{"WALLS"}, {}})
      .scaled(size * metres_per_unit(read_as) / metres_per_unit(drawn_in));
}

// Fewer candidates and points than the job uses: the office is small and clear.
PlanUnitFitOptions quick() {
  PlanUnitFitOptions o;
  o.registration.candidates = 4;
  o.registration.max_points = 1500;
  return o;
}

// The run's decision on the office's walls drawn in `drawn_in` and read as `read_as` (at
// `size` times their true size), between `candidates`, near `scale` (1 when unset).
PlanUnitDecision decide(PlanUnit drawn_in, PlanUnit read_as,
                        const std::vector<PlanUnitCandidate>& candidates, double size = 1.0,
                        std::optional<double> scale = std::nullopt,
                        const PlanUnitFitOptions& options = quick()) {
  return fit_plan_units(office().gridmap, read_plan(drawn_in, read_as, size), read_as, candidates,
                        scale, RasterizeOptions{}, options);
}

const PlanUnitFit& fit_of(const PlanUnitDecision& d, PlanUnit unit) {
  for (const PlanUnitFit& f : d.fits) {
    if (f.unit == unit)
      return f;
  }
  throw std::runtime_error("no fit for the unit");
}

TEST(PlanUnitFit, TheRunOverrulesADrawingReadInTheWrongUnit) {
  // Drawn in mm, read as cm (the drawing's evidence favoured cm).
  const std::vector<PlanUnitCandidate> candidates = {{PlanUnit::cm, 3.8, 0.56},
                                                     {PlanUnit::mm, 3.5, 0.40}};
  const PlanUnitDecision d = decide(PlanUnit::mm, PlanUnit::cm, candidates);
  EXPECT_TRUE(d.overruled()) << d.reason;
  EXPECT_FALSE(d.confirmed);
  EXPECT_EQ(d.unit, PlanUnit::mm) << d.reason;
  const PlanUnitFit& mm = fit_of(d, PlanUnit::mm);
  ASSERT_TRUE(mm.tried);
  // The scale found under mm is the plan's true scale (the preset's unit error of a few %).
  EXPECT_NEAR(mm.floorplan_scale * office().plan_scale, 1.0, 0.005);
  EXPECT_GT(mm.score, fit_of(d, PlanUnit::cm).score + 0.3);
}

TEST(PlanUnitFit, TheRunConfirmsARightUnit) {
  const std::vector<PlanUnitCandidate> candidates = {{PlanUnit::m, 3.5, 0.73},
                                                     {PlanUnit::ft, 2.5, 0.27}};
  const PlanUnitDecision d = decide(PlanUnit::m, PlanUnit::m, candidates);
  EXPECT_FALSE(d.overruled()) << d.reason;
  EXPECT_TRUE(d.confirmed) << d.reason;
  EXPECT_EQ(d.unit, PlanUnit::m);
  ASSERT_EQ(d.fits.size(), 2u);
  EXPECT_LT(fit_of(d, PlanUnit::ft).score, 0.25);
}

TEST(PlanUnitFit, APlanAtNoTrueSizeIsLeftToTheScaleSearch) {
  // Drawn in m at twice its size: neither m nor ft fits near scale 1 (ft would need 1.64).
  const std::vector<PlanUnitCandidate> candidates = {{PlanUnit::m, 3.5, 0.73},
                                                     {PlanUnit::ft, 2.5, 0.27}};
  const PlanUnitDecision d = decide(PlanUnit::m, PlanUnit::m, candidates, 2.0);
  EXPECT_FALSE(d.overruled()) << d.reason;
  EXPECT_FALSE(d.confirmed) << d.reason;
  EXPECT_EQ(d.unit, PlanUnit::m);
  // A given scale is where the units are tried instead.
  const PlanUnitDecision given =
      decide(PlanUnit::m, PlanUnit::m, candidates, 2.0, 0.5 / office().plan_scale);
  EXPECT_TRUE(given.confirmed) << given.reason;
}

TEST(PlanUnitFit, TheDrawingsUnitIsTriedEvenWhenNotACandidate) {
  const std::vector<PlanUnitCandidate> candidates = {{PlanUnit::cm, 3.0, 0.9},
                                                     {PlanUnit::in, 1.0, 0.1}};
  const PlanUnitDecision d = decide(PlanUnit::m, PlanUnit::m, candidates);
  ASSERT_EQ(d.fits.size(), 3u);
  EXPECT_EQ(d.fits.front().unit, PlanUnit::m);
  EXPECT_TRUE(d.confirmed) << d.reason;
}

TEST(PlanUnitFit, BadOptionsNameTheirField) {
  const std::vector<PlanUnitCandidate> candidates = {{PlanUnit::m, 1.0, 0.5},
                                                     {PlanUnit::ft, 1.0, 0.5}};
  const auto fit = [&](const PlanUnitFitOptions& o) {
    decide(PlanUnit::m, PlanUnit::m, candidates, 1.0, std::nullopt, o);
  };
  PlanUnitFitOptions margin;
  margin.scale_margin = 1.0;  // would search no scale at all
  test::expect_input_error([&] { fit(margin); }, {"units.scale_margin"});
  PlanUnitFitOptions score;
  score.min_score = 2.0;
  test::expect_input_error([&] { fit(score); }, {"units.min_score"});
  PlanUnitFitOptions cells;
  cells.max_cells = 10;
  test::expect_input_error([&] { fit(cells); }, {"units.max_cells"});
}

}  // namespace
}  // namespace floorgrid
