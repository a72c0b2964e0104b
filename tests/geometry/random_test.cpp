#include "floorgrid/core/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace floorgrid {
namespace {

TEST(Random, SameSeedSameNumbersDifferentSeedDifferent) {
  Random a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const double x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    EXPECT_EQ(a.normal(), b.normal());
    (void)c;
  }
  Random d(42), e(43);
  int equal = 0;
  for (int i = 0; i < 100; ++i)
    equal += d.uniform() == e.uniform();
  EXPECT_LT(equal, 2);
}

TEST(Random, UniformAndNormalMoments) {
  Random r(7);
  const int n = 200000;
  double sum = 0, sum_sq = 0, nsum = 0, nsum_sq = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_sq += u * u;
    const double z = r.normal(2.0);
    nsum += z;
    nsum_sq += z * z;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum_sq / n - 0.25, 1.0 / 12.0, 0.002);
  EXPECT_NEAR(nsum / n, 0.0, 0.02);
  EXPECT_NEAR(std::sqrt(nsum_sq / n), 2.0, 0.02);
}

TEST(Random, IntegerCoversRangeInclusive) {
  Random r(3);
  std::vector<int> hits(5, 0);
  for (int i = 0; i < 5000; ++i) {
    const auto k = r.integer(-2, 2);
    ASSERT_GE(k, -2);
    ASSERT_LE(k, 2);
    ++hits[static_cast<std::size_t>(k + 2)];
  }
  for (int h : hits)
    EXPECT_NEAR(h, 1000, 150);
}

}  // namespace
}  // namespace floorgrid
