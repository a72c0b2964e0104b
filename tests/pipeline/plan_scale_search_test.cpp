// The top of the dead reckoning's counts over the candidate scales (hump_top): analytic humps
// with and without noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "floorgrid/pipeline/plan_scale_search.hpp"

namespace floorgrid {
namespace {

/// 41 scales over 1.18 +- 9.3% (fr079's lattice) and counts of a hump peaking at `top`
/// (20000 there, falling by `fall` per square percent away), plus `noise` times a fixed +-1
/// zig-zag (+1, -1, -1, +1, ...: no parabola follows it) and `spike` more at the candidate
/// nearest 3% above the top.
struct Hump {
  std::vector<double> scales;
  std::vector<std::size_t> counts;
};

Hump make_hump(double top, double fall, double noise, double spike = 0.0) {
  Hump h;
  for (int k = -20; k <= 20; ++k) {
    const double s = 1.18 * (1.0 + 0.093 * k / 20.0);
    const double off = 100.0 * (s / top - 1.0);
    const double pattern = (k % 4 == 0 || k % 4 == 3 || k % 4 == -1) ? 1.0 : -1.0;
    const double up = std::abs(off - 3.0) < 0.25 ? spike : 0.0;
    h.scales.push_back(s);
    h.counts.push_back(
        static_cast<std::size_t>(std::max(0.0, 20000.0 - fall * off * off + noise * pattern + up)));
  }
  return h;
}

TEST(HumpTop, FindsTheVertexOfAParabolaBetweenTheLatticesSteps) {
  const Hump h = make_hump(1.1372, 150.0, 0.0);  // between two candidates (1.1364, 1.1420)
  EXPECT_NEAR(hump_top(h.scales, h.counts, 0.3), 1.1372, 1.1372 * 2e-4);
}

TEST(HumpTop, FollowsTheHumpWhereTheLargestCountFollowsTheNoise) {
  // A found or lost match moves a count by thousands (fr079's fell from 16,800 to 5,515 between
  // neighbouring scales): here one candidate 3% above the top is 2500 up, so the largest count
  // is there; the fit over the hump stays at its top.
  const Hump h = make_hump(1.15, 150.0, 500.0, 2500.0);
  std::size_t best = 0;
  for (std::size_t k = 1; k < h.counts.size(); ++k) {
    if (h.counts[k] > h.counts[best])
      best = k;
  }
  ASSERT_GT(h.scales[best] / 1.15 - 1.0, 0.025);  // the largest count is the spike
  EXPECT_NEAR(hump_top(h.scales, h.counts, 0.3), 1.15, 1.15 * 0.002);
}

TEST(HumpTop, ATopAtTheRangesEdgeIsTheLargestCount) {
  // Counts that only rise: the parabola's vertex would lie beyond the candidates.
  Hump h;
  for (int k = 0; k < 21; ++k) {
    h.scales.push_back(1.0 + 0.01 * k);
    h.counts.push_back(static_cast<std::size_t>(1000 + 50 * k));
  }
  EXPECT_DOUBLE_EQ(hump_top(h.scales, h.counts, 0.3), h.scales.back());
}

TEST(HumpTop, AValleyIsNotATop) {
  // A parabola that opens upwards has no top: the largest count is kept.
  Hump h;
  for (int k = -10; k <= 10; ++k) {
    h.scales.push_back(1.0 + 0.01 * k);
    h.counts.push_back(static_cast<std::size_t>(1000 + 10 * k * k + (k == -10 ? 5 : 0)));
  }
  EXPECT_DOUBLE_EQ(hump_top(h.scales, h.counts, 0.0), h.scales.front());
}

TEST(HumpTop, NoCandidatesIsAnError) {
  EXPECT_THROW(hump_top({}, {}, 0.3), std::invalid_argument);
  EXPECT_THROW(hump_top({1.0, 1.1}, {5}, 0.3), std::invalid_argument);
}

}  // namespace
}  // namespace floorgrid
