#include "floorgrid/geometry/residual_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

// Distances |e| of 2-D Gaussian noise e of `sigma` per axis (Rayleigh(sigma)).
std::vector<double> rayleigh(int count, double sigma, std::uint64_t seed) {
  Random random(seed);
  std::vector<double> d(static_cast<std::size_t>(count));
  for (double& x : d)
    x = std::hypot(random.normal(sigma), random.normal(sigma));
  return d;
}

TEST(ResidualScale, RecoversSigmaWhateverTheCut) {
  // 10^5 distances: the median's own spread is about 0.5%.
  for (const double cut_in_sigmas : {0.7, 1.0, 2.0, 3.0, 10.0, 1e6}) {
    std::vector<double> d = rayleigh(100000, 0.3, 1);
    const std::optional<double> sigma = truncated_rayleigh_scale(d, cut_in_sigmas * 0.3, 0);
    ASSERT_TRUE(sigma.has_value()) << cut_in_sigmas;
    EXPECT_NEAR(*sigma, 0.3, 0.3 * 0.03) << cut_in_sigmas;
  }
}

TEST(ResidualScale, IgnoresWhatLiesBeyondTheCut) {
  std::vector<double> d = rayleigh(10000, 0.05, 2);
  Random random(3);
  for (int i = 0; i < 30000; ++i)  // three outliers to an inlier, all far
    d.push_back(random.uniform(1.0, 50.0));
  const std::optional<double> sigma = truncated_rayleigh_scale(d, 0.2, 0);
  ASSERT_TRUE(sigma.has_value());
  EXPECT_NEAR(*sigma, 0.05, 0.05 * 0.03);
}

TEST(ResidualScale, ScalesWithTheNoise) {
  std::vector<double> small = rayleigh(5000, 0.02, 4);
  std::vector<double> large = small;
  for (double& x : large)
    x *= 10.0;
  const std::optional<double> a = truncated_rayleigh_scale(small, 0.06, 4);
  const std::optional<double> b = truncated_rayleigh_scale(large, 0.6, 4);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(*b / *a, 10.0, 1e-9);
}

TEST(ResidualScale, CorrectsForTheParametersFitted) {
  // Ten distances with a median of 1 well inside the cut: sigma = 1 / sqrt(2 ln 2), inflated by
  // sqrt(2 * 10 / (2 * 10 - 4)).
  std::vector<double> d = {0.2, 0.4, 0.6, 0.8, 0.9, 1.1, 1.3, 1.6, 2.0, 2.5, 900.0};
  const std::optional<double> sigma = truncated_rayleigh_scale(d, 100.0, 4);
  ASSERT_TRUE(sigma.has_value());
  EXPECT_NEAR(*sigma, std::sqrt(20.0 / 16.0) / std::sqrt(2.0 * std::numbers::ln2), 1e-6);
}

TEST(ResidualScale, NotIdentifiableWhenTheDistancesFillTheCutOrAreTooFew) {
  // Spread evenly over the disc of the cut: the noise could be any size above it.
  Random random(5);
  std::vector<double> even(2000);
  for (double& x : even)
    x = std::sqrt(random.uniform());
  EXPECT_FALSE(truncated_rayleigh_scale(even, 1.0, 4).has_value());
  std::vector<double> few = {0.1, 0.2, 0.3, 0.4, 0.5, 7.0};
  EXPECT_FALSE(truncated_rayleigh_scale(few, 1.0, 4).has_value());  // 5 within: not 4 + 2
  std::vector<double> exact(100, 0.0);
  EXPECT_EQ(truncated_rayleigh_scale(exact, 1.0, 4), 0.0);
}

}  // namespace
}  // namespace floorgrid
