#include "floorgrid/core/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace floorgrid {
namespace {

TEST(Median, OddCountIsTheMiddleValue) {
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median({7.0}), 7.0);
}

TEST(Median, EvenCountIsTheMeanOfTheTwoMiddleValues) {
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({-1.0, 1.0}), 0.0);
  // Repeated middle values.
  EXPECT_DOUBLE_EQ(median({2.0, 2.0, 9.0, 0.0}), 2.0);
}

TEST(Median, EmptyIsNaN) {
  EXPECT_TRUE(std::isnan(median({})));
}

TEST(UpperMedian, IsAlwaysOneOfTheValues) {
  EXPECT_DOUBLE_EQ(upper_median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(upper_median({4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_DOUBLE_EQ(upper_median({0.05, 0.10}), 0.10);
  EXPECT_TRUE(std::isnan(upper_median({})));
}

TEST(Quantile, InterpolatesBetweenSortedValuesLikeNumpy) {
  // numpy.quantile([1, 2, 3, 4], [0, 0.25, 0.5, 0.95, 1]) = 1, 1.75, 2.5, 3.85, 4
  const std::vector<double> v{4.0, 2.0, 1.0, 3.0};
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.25), 1.75);
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 2.5);
  EXPECT_NEAR(quantile(v, 0.95), 3.85, 1e-12);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 4.0);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

}  // namespace
}  // namespace floorgrid
