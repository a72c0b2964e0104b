#include "floorgrid/localization/convergence.hpp"

#include <gtest/gtest.h>

#include <iterator>
#include <limits>

#include "floorgrid/localization/divergence.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

// An estimate that meets every default criterion.
PoseEstimate good_estimate() {
  PoseEstimate e;
  e.position_std = 0.1;
  e.heading_std = 0.03;
  e.scale_std = 0.005;
  e.ess_ratio = 0.5;
  e.particles = 1000;
  return e;
}

TEST(Convergence, EachCriterionCanFail) {
  const ConvergenceOptions o;
  EXPECT_TRUE(check_convergence(good_estimate(), 0.8, true, o).criteria_met);

  PoseEstimate e = good_estimate();
  e.position_std = 0.31;
  ConvergenceCheck c = check_convergence(e, 0.8, false, o);
  EXPECT_FALSE(c.position_ok);
  EXPECT_FALSE(c.criteria_met);

  e = good_estimate();
  e.heading_std = 0.11;
  EXPECT_FALSE(check_convergence(e, 0.8, false, o).heading_ok);

  e = good_estimate();
  e.ess_ratio = 0.04;
  EXPECT_FALSE(check_convergence(e, 0.8, false, o).ess_ok);

  c = check_convergence(good_estimate(), 0.29, false, o);
  EXPECT_FALSE(c.beam_ok);
  EXPECT_FALSE(c.criteria_met);

  e = good_estimate();
  e.position_std = std::numeric_limits<double>::quiet_NaN();  // NaN never passes
  EXPECT_FALSE(check_convergence(e, 0.8, false, o).position_ok);
}

TEST(Convergence, ScaleIsCheckedOnlyWhenTheParticlesCarryOne) {
  PoseEstimate e = good_estimate();
  e.scale_std = 0.05;
  EXPECT_FALSE(check_convergence(e, 0.8, true, {}).criteria_met);
  EXPECT_TRUE(check_convergence(e, 0.8, false, {}).criteria_met);
}

TEST(Convergence, HysteresisNeedsMinConvergedScansInARow) {
  // 3 passing scans in a row to converge; the first failing scan ends it (no rejoining).
  ConvergenceOptions o;
  o.rejoin_window = 0;
  ConvergenceMonitor m(o);
  const PoseEstimate good = good_estimate();
  const bool pass_pattern[] = {true, true, false, true, true, true, true, false, true, true, true};
  const bool expected[] = {false, false, false, false, false, true,
                           true,  false, false, false, true};
  for (std::size_t i = 0; i < std::size(pass_pattern); ++i) {
    const ConvergenceCheck& c = m.update(good, pass_pattern[i] ? 0.8 : 0.1, false);
    EXPECT_EQ(c.converged, expected[i]) << "scan " << i;
    EXPECT_EQ(m.converged(), expected[i]);
  }
  EXPECT_EQ(m.last().consecutive_met, 3);
  m.reset();
  EXPECT_FALSE(m.converged());
  EXPECT_EQ(m.last().consecutive_met, 0);
}

TEST(Convergence, HysteresisToleratesMaxFailedScansMinusOne) {
  ConvergenceOptions o;
  o.min_converged_scans = 2;
  o.max_failed_scans = 2;
  o.rejoin_window = 0;
  ConvergenceMonitor m(o);
  const PoseEstimate good = good_estimate();
  const double beam[] = {0.8, 0.8, 0.1, 0.8, 0.1, 0.1, 0.8, 0.8};
  const bool expected[] = {false, true, true, true, true, false, false, true};
  for (std::size_t i = 0; i < std::size(beam); ++i)
    EXPECT_EQ(m.update(good, beam[i], false).converged, expected[i]) << "scan " << i;
}

TEST(Convergence, AFilterThatDroppedForAScanOrTwoRejoinsAfterOneGoodScan) {
  // Defaults: 3 passing scans to converge; after at most rejoin_window (2) failing scans, one
  // passing scan rejoins; after more, or after a reset, it takes 3 again.
  ConvergenceMonitor m;
  const PoseEstimate good = good_estimate();
  const bool pass_pattern[] = {true, true,  true,  false, true, false, false,
                               true, false, false, false, true, true,  true};
  const bool expected[] = {false, false, true,  false, true,  false, false,
                           true,  false, false, false, false, false, true};
  for (std::size_t i = 0; i < std::size(pass_pattern); ++i)
    EXPECT_EQ(m.update(good, pass_pattern[i] ? 0.8 : 0.1, false).converged, expected[i])
        << "scan " << i;
  // A reset (a re-initialized or diverged filter) forgets the hypothesis it had.
  m.update(good, 0.1, false);
  m.reset();
  EXPECT_FALSE(m.update(good, 0.8, false).converged);
}

TEST(Convergence, ABlindFilterStaysConvergedForAtMostMaxBlindScans) {
  // NaN: the map cannot judge the scan (every endpoint off its known area). By default a
  // converged filter stays converged through any number of such scans; with max_blind_scans 4
  // it stops after the fourth, cannot converge while blind, and needs min_converged_scans
  // judged scans to converge again.
  const double blind = std::numeric_limits<double>::quiet_NaN();
  const PoseEstimate good = good_estimate();
  ConvergenceMonitor keeps;  // max_blind_scans 0: never
  for (int i = 0; i < 3; ++i)
    keeps.update(good, 0.8, false);
  ASSERT_TRUE(keeps.converged());
  for (int i = 0; i < 50; ++i)
    EXPECT_TRUE(keeps.update(good, blind, false).converged) << "blind scan " << i;

  ConvergenceOptions o;
  o.max_blind_scans = 4;
  ConvergenceMonitor m(o);
  for (int i = 0; i < 3; ++i)
    m.update(good, 0.8, false);
  ASSERT_TRUE(m.converged());
  for (int i = 1; i <= 8; ++i) {
    const ConvergenceCheck& c = m.update(good, blind, false);
    EXPECT_EQ(c.consecutive_blind, i);
    EXPECT_EQ(c.converged, i <= 4) << "blind scan " << i;
  }
  // Judged again: three passing scans to converge (the blind stretch was longer than
  // rejoin_window).
  EXPECT_FALSE(m.update(good, 0.8, false).converged);
  EXPECT_EQ(m.last().consecutive_blind, 0);
  EXPECT_FALSE(m.update(good, 0.8, false).converged);
  EXPECT_TRUE(m.update(good, 0.8, false).converged);
  // A short blind stretch (at most 4 scans) keeps it converged, and a judged scan between two
  // stretches starts the count again.
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(m.update(good, blind, false).converged);
  EXPECT_TRUE(m.update(good, 0.8, false).converged);
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(m.update(good, blind, false).converged);
}

TEST(Convergence, RejectsBadOptions) {
  ConvergenceOptions o;
  o.min_converged_scans = 0;
  test::expect_input_error([&] { validate(o); }, {"convergence.min_converged_scans", ">= 1"});
  o = {};
  o.min_ess_ratio = 1.5;
  test::expect_input_error([&] { ConvergenceMonitor m(o); }, {"convergence.min_ess_ratio"});
  o = {};
  o.max_position_std = -1;
  test::expect_input_error([&] { validate(o); }, {"convergence.max_position_std", "-1"});
  o = {};
  o.rejoin_window = -1;
  test::expect_input_error([&] { validate(o); }, {"convergence.rejoin_window", ">= 0"});
  o = {};
  o.min_rejoin_scans = 0;
  test::expect_input_error([&] { validate(o); }, {"convergence.min_rejoin_scans", ">= 1"});
  o = {};
  o.max_blind_scans = -2;
  test::expect_input_error([&] { validate(o); }, {"convergence.max_blind_scans", ">= 0"});
}

TEST(ConvergenceDivergence, BadScansInARowMeanDiverged) {
  DivergenceMonitor m;  // default: 5 scans below 0.15
  const PoseEstimate e = good_estimate();
  for (int i = 0; i < 4; ++i)
    EXPECT_FALSE(m.update(0.1, e, false).diverged()) << i;
  EXPECT_EQ(m.last().bad_scans, 4);
  EXPECT_FALSE(m.update(0.5, e, false).diverged());  // a good scan resets the count
  EXPECT_EQ(m.last().bad_scans, 0);
  for (int i = 0; i < 4; ++i)
    m.update(0.05, e, false);
  const DivergenceCheck& c = m.update(0.05, e, false);
  EXPECT_TRUE(c.diverged());
  EXPECT_EQ(c.reason, DivergenceReason::low_likelihood);
  EXPECT_EQ(to_string(c.reason), "low_likelihood");
}

TEST(ConvergenceDivergence, SpreadAndRatioSignalsNeedAConvergedFilter) {
  PoseEstimate wide = good_estimate();
  wide.position_std = 2.0;
  DivergenceMonitor m;
  EXPECT_FALSE(m.update(0.8, wide, false).diverged());  // never converged: no spread signal
  EXPECT_EQ(m.update(0.8, wide, true).reason, DivergenceReason::spread);

  // Ratio: w_slow ~ 0.8 after a long good stretch; a drop to 0.16 takes w_fast below
  // 0.3 * w_slow within a few scans (alpha_fast 0.2: w_fast = 0.16 + 0.64 * 0.8^k).
  RecoveryOptions o;
  o.max_bad_scans = 1000;  // isolate the ratio signal
  DivergenceMonitor r(o);
  const PoseEstimate good = good_estimate();
  for (int i = 0; i < 50; ++i)
    r.update(0.8, good, true);
  EXPECT_NEAR(r.last().fast_slow_ratio, 1.0, 1e-12);
  EXPECT_EQ(r.last().augmented_fraction, 0.0);
  int scans = 0;
  while (!r.update(0.16, good, true).diverged() && scans < 100)
    ++scans;
  EXPECT_EQ(r.last().reason, DivergenceReason::likelihood_drop);
  EXPECT_LT(scans, 15);
  // On the way the augmented fraction grew, capped at max_augmented_fraction.
  EXPECT_DOUBLE_EQ(r.last().augmented_fraction, o.max_augmented_fraction);
  // Not converged: the same drop is no divergence signal (the bad-scan count stays armed).
  DivergenceMonitor q(o);
  for (int i = 0; i < 50; ++i)
    q.update(0.8, good, false);
  for (int i = 0; i < 30; ++i)
    EXPECT_FALSE(q.update(0.16, good, false).diverged());
}

TEST(ConvergenceDivergence, AugmentedFractionIsOneMinusTheRatio) {
  RecoveryOptions o;
  o.alpha_slow = 0.5;
  o.alpha_fast = 1.0;  // w_fast is the last value
  o.max_augmented_fraction = 1.0;
  DivergenceMonitor m(o);
  m.update(0.8, good_estimate(), false);  // both averages start at 0.8
  const DivergenceCheck& c = m.update(0.4, good_estimate(), false);
  // w_slow = 0.8 + 0.5 (0.4 - 0.8) = 0.6, w_fast = 0.4: ratio 2/3.
  EXPECT_NEAR(c.fast_slow_ratio, 0.4 / 0.6, 1e-12);
  EXPECT_NEAR(c.augmented_fraction, 1.0 - 0.4 / 0.6, 1e-12);
}

TEST(ConvergenceDivergence, DisabledNeverDiverges) {
  RecoveryOptions o;
  o.enabled = false;
  DivergenceMonitor m(o);
  for (int i = 0; i < 20; ++i) {
    EXPECT_FALSE(m.update(0.0, good_estimate(), true).diverged());
    EXPECT_EQ(m.last().augmented_fraction, 0.0);
  }
}

TEST(ConvergenceDivergence, RejectsBadOptions) {
  RecoveryOptions o;
  o.alpha_fast = 0.005;  // below alpha_slow
  test::expect_input_error([&] { validate(o); }, {"recovery.alpha_fast"});
  o = {};
  o.radius_growth = 0.5;
  test::expect_input_error([&] { DivergenceMonitor m(o); }, {"recovery.radius_growth", ">= 1"});
}

}  // namespace
}  // namespace floorgrid
