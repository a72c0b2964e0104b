#include "floorgrid/core/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace floorgrid {
namespace {

TEST(Random, TheSameSeedGivesTheSameNumbers) {
  Random a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    differs = differs || x != c.uniform();
  }
  EXPECT_TRUE(differs);
}

TEST(Random, UniformAndNormalHaveTheirMoments) {
  Random r(7);
  const int n = 200000;
  double su = 0, su2 = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform(2.0, 5.0);
    ASSERT_GE(u, 2.0);
    ASSERT_LT(u, 5.0);
    su += u, su2 += u * u;
    const double g = r.normal(0.5);
    sn += g, sn2 += g * g;
  }
  // Uniform on [2, 5): mean 3.5, variance 0.75; normal(0.5): mean 0, variance 0.25. Within
  // about 5 standard errors.
  EXPECT_NEAR(su / n, 3.5, 5 * std::sqrt(0.75 / n));
  EXPECT_NEAR(su2 / n - (su / n) * (su / n), 0.75, 0.01);
  EXPECT_NEAR(sn / n, 0.0, 5 * 0.5 / std::sqrt(n));
  EXPECT_NEAR(sn2 / n, 0.25, 0.005);
}

TEST(Random, IntegersCoverTheirInclusiveRangeEvenly) {
  Random r(9);
  std::vector<int> counts(5, 0);
  for (int i = 0; i < 50000; ++i) {
    const auto k = r.integer(-2, 2);
    ASSERT_GE(k, -2);
    ASSERT_LE(k, 2);
    ++counts[static_cast<std::size_t>(k + 2)];
  }
  for (const int c : counts)
    EXPECT_NEAR(c, 10000, 500);
  EXPECT_EQ(r.integer(3, 3), 3);
}

}  // namespace
}  // namespace floorgrid
