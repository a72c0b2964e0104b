#include "floorgrid/localization/resampling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace floorgrid {
namespace {

std::vector<std::size_t> copy_counts(const std::vector<std::size_t>& indices, std::size_t n) {
  std::vector<std::size_t> counts(n, 0);
  for (const std::size_t i : indices)
    ++counts[i];
  return counts;
}

std::vector<double> random_weights(std::size_t n, Random& random) {
  std::vector<double> w(n);
  double total = 0.0;
  for (double& wi : w) {
    // Spread over three orders of magnitude, some exactly zero.
    wi = random.bernoulli(0.1) ? 0.0 : std::pow(10.0, random.uniform(-3.0, 0.0));
    total += wi;
  }
  for (double& wi : w)
    wi /= total;
  return w;
}

TEST(Resampling, SystematicCopyCountsAreWithinOneOfCountTimesTheWeight) {
  // Systematic resampling's defining property (thesis 3.5.4): the equally spaced pointers hit a
  // slice of width count * w_i (in pointer spacings) floor(count w_i) or ceil(count w_i) times,
  // whatever the offset. Checked for counts below, at and above N, and offsets at both ends.
  Random random(3);
  const std::size_t n = 1000;
  const std::vector<double> w = random_weights(n, random);
  std::vector<std::size_t> indices;
  for (const std::size_t count : {n, n / 3, 2 * n + 7}) {
    for (const double offset : {0.0, 0.25, 0.5, 0.999999, random.uniform(), random.uniform()}) {
      systematic_resample(w, count, offset, indices);
      ASSERT_EQ(indices.size(), count);
      const std::vector<std::size_t> counts = copy_counts(indices, n);
      for (std::size_t i = 0; i < n; ++i) {
        const double expected = static_cast<double>(count) * w[i];
        EXPECT_LE(std::abs(static_cast<double>(counts[i]) - expected), 1.0)
            << "particle " << i << " count " << count << " offset " << offset;
        if (w[i] == 0.0) {
          EXPECT_EQ(counts[i], 0u);
        }
      }
      for (std::size_t j = 1; j < count; ++j)
        ASSERT_LE(indices[j - 1], indices[j]);  // ascending
    }
  }
}

TEST(Resampling, CopyCountsAreUnbiasedOverTheOffset) {
  // Over a uniform offset the expected count is exactly count * w_i. Each count is one of two
  // neighbouring integers (variance <= 1/4), so the mean of M draws has a standard deviation
  // <= 0.5 / sqrt(M) = 0.0035 for M = 20000; 0.02 is more than 5 of them.
  Random random(8);
  const std::vector<double> w = {0.05, 0.3, 0.0, 0.015, 0.235, 0.4};
  const std::size_t count = 7;
  std::vector<double> mean(w.size(), 0.0);
  std::vector<std::size_t> indices;
  const int draws = 20000;
  for (int d = 0; d < draws; ++d) {
    low_variance_resample(w, count, random, indices);
    const std::vector<std::size_t> counts = copy_counts(indices, w.size());
    for (std::size_t i = 0; i < w.size(); ++i)
      mean[i] += static_cast<double>(counts[i]) / draws;
  }
  for (std::size_t i = 0; i < w.size(); ++i)
    EXPECT_NEAR(mean[i], static_cast<double>(count) * w[i], 0.02) << "particle " << i;
}

TEST(Resampling, KnownWheel) {
  // The thesis's roulette wheel by hand: weights 0.1, 0.4, 0.0, 0.5 and 4 pointers at
  // (0.5 + j) / 4 = 0.125, 0.375, 0.625, 0.875 land in slices 1, 1, 3, 3.
  std::vector<std::size_t> indices;
  systematic_resample(std::vector<double>{0.1, 0.4, 0.0, 0.5}, 4, 0.5, indices);
  EXPECT_EQ(indices, (std::vector<std::size_t>{1, 1, 3, 3}));
  // Unnormalized weights give the same picks.
  systematic_resample(std::vector<double>{1.0, 4.0, 0.0, 5.0}, 4, 0.5, indices);
  EXPECT_EQ(indices, (std::vector<std::size_t>{1, 1, 3, 3}));
  // Trailing zero weights are never picked, even by the last pointer.
  systematic_resample(std::vector<double>{0.0, 1.0, 0.0, 0.0}, 5, 0.999999999, indices);
  EXPECT_EQ(indices, (std::vector<std::size_t>(5, 1)));
}

TEST(Resampling, DeterministicForASeed) {
  Random weights_random(1);
  const std::vector<double> w = random_weights(500, weights_random);
  std::vector<std::size_t> a, b, c;
  Random r1(42), r2(42), r3(43);
  low_variance_resample(w, 500, r1, a);
  low_variance_resample(w, 500, r2, b);
  low_variance_resample(w, 500, r3, c);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Resampling, GatherCopiesThePickedParticlesWithEqualWeights) {
  ParticleSet from;
  from.x = {0, 1, 2};
  from.y = {10, 11, 12};
  from.theta = {0.1, 0.2, 0.3};
  from.scale = {1.01, 1.02, 1.03};
  from.weight = {0.2, 0.3, 0.5};
  ParticleSet to;
  const std::vector<std::size_t> indices = {2, 2, 0, 1};
  gather_particles(from, indices, to);
  ASSERT_EQ(to.size(), 4u);
  EXPECT_EQ(to.x, (std::vector<double>{2, 2, 0, 1}));
  EXPECT_EQ(to.y, (std::vector<double>{12, 12, 10, 11}));
  EXPECT_EQ(to.theta, (std::vector<double>{0.3, 0.3, 0.1, 0.2}));
  EXPECT_EQ(to.scale, (std::vector<double>{1.03, 1.03, 1.01, 1.02}));
  EXPECT_EQ(to.weight, (std::vector<double>(4, 0.25)));
  // Without a scale the target has none, even when it had one before.
  from.scale.clear();
  gather_particles(from, indices, to);
  EXPECT_FALSE(to.has_scale());
}

}  // namespace
}  // namespace floorgrid
