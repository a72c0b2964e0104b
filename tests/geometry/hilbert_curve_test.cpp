#include "floorgrid/geometry/hilbert_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <utility>
#include <vector>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

TEST(HilbertCurve, VisitsEveryCellOnceThroughNeighbouringCells) {
  for (const int bits : {1, 2, 3, 5, 7}) {
    const int side = 1 << bits;
    std::vector<std::array<int, 2>> cell_at(static_cast<std::size_t>(side) * side, {-1, -1});
    for (int x = 0; x < side; ++x) {
      for (int y = 0; y < side; ++y) {
        const std::uint64_t d =
            hilbert_index(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), bits);
        ASSERT_LT(d, cell_at.size());
        ASSERT_EQ(cell_at[d][0], -1) << "index " << d << " twice";
        cell_at[d] = {x, y};
      }
    }
    for (std::size_t d = 1; d < cell_at.size(); ++d) {
      const int step =
          std::abs(cell_at[d][0] - cell_at[d - 1][0]) + std::abs(cell_at[d][1] - cell_at[d - 1][1]);
      ASSERT_EQ(step, 1) << "bits " << bits << " index " << d;
    }
    EXPECT_EQ(cell_at.front(), (std::array<int, 2>{0, 0}));
  }
}

// The textbook formulation with explicit rotations, as a reference for the branch-free one.
std::uint64_t reference_index(std::uint32_t x, std::uint32_t y, int bits) {
  const std::uint32_t top = (1u << bits) - 1u;
  std::uint64_t d = 0;
  for (std::uint32_t s = 1u << (bits - 1); s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1u : 0u;
    const std::uint32_t ry = (y & s) ? 1u : 0u;
    d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = top - x;
        y = top - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

TEST(HilbertCurve, MatchesTheTextbookFormulation) {
  Random random(4);
  for (int i = 0; i < 100000; ++i) {
    const auto x = static_cast<std::uint32_t>(random.integer(0, (1 << kHilbertBits) - 1));
    const auto y = static_cast<std::uint32_t>(random.integer(0, (1 << kHilbertBits) - 1));
    ASSERT_EQ(hilbert_index(x, y, kHilbertBits), reference_index(x, y, kHilbertBits));
  }
}

TEST(HilbertCurve, RadixSortMatchesStableSort) {
  Random random(6);
  const Eigen::Index n = 50000;
  Eigen::Matrix2Xd p(2, n);
  for (Eigen::Index i = 0; i < n; ++i)
    p.col(i) << std::round(random.uniform(0, 300)), random.uniform(-1e3, 1e3);
  const std::vector<std::uint64_t> keys = hilbert_keys(p);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>((i * 7919) % order.size());  // a permutation
  std::vector<int> expected = order;
  sort_by_hilbert_key(order.begin() + 10, order.end(), keys);
  std::stable_sort(expected.begin() + 10, expected.end(), [&](int a, int b) {
    return keys[static_cast<std::size_t>(a)] < keys[static_cast<std::size_t>(b)];
  });
  EXPECT_EQ(order, expected);
}

TEST(HilbertCurve, SortingIsStable) {
  Eigen::Matrix2Xd p(2, 6);
  p << 0, 1, 0, 1, 0, 0.5, 0, 0, 1, 1, 0, 0.5;  // point 4 repeats point 0
  const std::vector<std::uint64_t> keys = hilbert_keys(p);
  EXPECT_EQ(keys[0], keys[4]);
  std::vector<int> order(6);
  std::iota(order.begin(), order.end(), 0);
  std::reverse(order.begin(), order.end());
  sort_by_hilbert_key(order.begin(), order.end(), keys);
  EXPECT_EQ(order[0], 4);  // equal keys keep their input order
  EXPECT_EQ(order[1], 0);
  for (std::size_t i = 1; i < order.size(); ++i)
    EXPECT_LE(keys[static_cast<std::size_t>(order[i - 1])],
              keys[static_cast<std::size_t>(order[i])]);
}

}  // namespace
}  // namespace floorgrid
