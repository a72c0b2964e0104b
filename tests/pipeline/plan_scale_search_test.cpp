// The top of the dead reckoning's counts over the candidate scales (hump_top): analytic humps
// with and without noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "floorgrid/pipeline/plan_scale_search.hpp"

namespace floorgrid {
namespace {

/// 41 scales over 1.18 +- 9.3% (fr079's lattice) and counts of a hump peaking at `top`
/// (20000 there, falling by `fall` per 1% away), plus `noise` times a fixed +-1 pattern.
struct Hump {
  std::vector<double> scales;
  std::vector<std::size_t> counts;
};

Hump make_hump(double top, double fall, double noise) {
  Hump h;
  for (int k = -20; k <= 20; ++k) {
    const double s = 1.18 * (1.0 + 0.093 * k / 20.0);
    const double off = 100.0 * (s / top - 1.0);
    // A deterministic zig-zag that no parabola follows: +1, -1, -1, +1, ...
    const double pattern = (k % 4 == 0 || k % 4 == 3 || k % 4 == -1) ? 1.0 : -1.0;
    h.scales.push_back(s);
    h.counts.push_back(
        static_cast<std::size_t>(std::max(0.0, 20000.0 - fall * off * off + noise * pattern)));
  }
  return h;
}

TEST(HumpTop, FindsTheVertexOfAParabolaBetweenTheLatticesSteps) {
  const Hump h = make_hump(1.1372, 150.0, 0.0);  // between two candidates (1.1364, 1.1420)
  EXPECT_NEAR(hump_top(h.scales, h.counts, 0.3), 1.1372, 1.1372 * 2e-4);
}

TEST(HumpTop, FollowsTheHumpWhereTheLargestCountFollowsTheNoise) {
  // Noise of +-1500 (fr079's counts jump by about that between neighbouring scales): the
  // largest count lands wherever the noise is up, the fit stays near the hump's top.
  const Hump h = make_hump(1.15, 150.0, 1500.0);
  std::size_t best = 0;
  for (std::size_t k = 1; k < h.counts.size(); ++k) {
    if (h.counts[k] > h.counts[best])
      best = k;
  }
  const double fitted = hump_top(h.scales, h.counts, 0.3);
  EXPECT_NEAR(fitted, 1.15, 1.15 * 0.004);
  EXPECT_LT(std::abs(fitted - 1.15), std::abs(h.scales[best] - 1.15) + 1e-12);
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

}  // namespace
}  // namespace floorgrid
