#include "floorgrid/pipeline/outlier_scans.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// 60 scans of 40 pairs each along the walls of a 20 m x 10 m box, the grid the plan through a
/// similarity with 1 cm of noise; the pairs of `shifted` scans moved by `shift` in the grid.
ReferencePairs scans_of_pairs(const std::vector<std::size_t>& shifted, const Eigen::Vector2d& shift,
                              std::vector<std::size_t>& per_scan) {
  Random random(5);
  const double c = std::cos(0.2), s = std::sin(0.2);
  std::vector<Eigen::Vector2d> plan, grid;
  per_scan.assign(60, 40);
  for (std::size_t scan = 0; scan < 60; ++scan) {
    // Each scan sees the stretch of wall around its place along the box's perimeter (60 m),
    // overlapping its neighbours'.
    const double start = static_cast<double>(scan);
    for (int k = 0; k < 40; ++k) {
      double u = std::fmod(start + 0.1 * k, 60.0);
      Eigen::Vector2d p;
      if (u < 20)
        p = {u, 0.0};
      else if (u < 30)
        p = {20.0, u - 20.0};
      else if (u < 50)
        p = {50.0 - u, 10.0};
      else
        p = {0.0, 60.0 - u};
      Eigen::Vector2d q(2.0 + 1.05 * (c * p.x() - s * p.y()),
                        -1.0 + 1.05 * (s * p.x() + c * p.y()));
      q += Eigen::Vector2d(random.normal(0.01), random.normal(0.01));
      if (std::find(shifted.begin(), shifted.end(), scan) != shifted.end())
        q += shift;
      plan.push_back(p);
      grid.push_back(q);
    }
  }
  return test::pairs_of(plan, grid);
}

TEST(OutlierScans, DropsTheScanThatDisagreesAndKeepsTheRest) {
  std::vector<std::size_t> per_scan;
  ReferencePairs pairs = scans_of_pairs({17}, {0.5, 0.0}, per_scan);
  const ReferencePairs before = pairs;
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 1u);
  EXPECT_EQ(per_scan[17], 0u);
  for (std::size_t s = 0; s < per_scan.size(); ++s) {
    if (s != 17) {
      EXPECT_EQ(per_scan[s], 40u) << s;
    }
  }
  ASSERT_EQ(pairs.size(), before.size() - 40);
  // The kept pairs are the others, in order.
  EXPECT_TRUE(
      pairs.points_in_plan.leftCols(17 * 40).isApprox(before.points_in_plan.leftCols(17 * 40)));
  EXPECT_TRUE(
      pairs.points_in_grid.rightCols(42 * 40).isApprox(before.points_in_grid.rightCols(42 * 40)));
}

TEST(OutlierScans, KeepsConsistentScansAndHonoursItsLimits) {
  std::vector<std::size_t> per_scan;
  ReferencePairs pairs = scans_of_pairs({}, Eigen::Vector2d::Zero(), per_scan);
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 0u);
  EXPECT_EQ(pairs.size(), 2400);
  // Disabled, or too few pairs: nothing is dropped.
  ReferencePairs shifted = scans_of_pairs({3}, {0.5, 0.0}, per_scan);
  EXPECT_EQ(reject_outlier_scans(shifted, per_scan, {.enabled = false}), 0u);
  EXPECT_EQ(reject_outlier_scans(shifted, per_scan, {.min_pairs = 10000}), 0u);
  // A shift within max_deviation (0.15 m) is not an outlier.
  ReferencePairs small = scans_of_pairs({3}, {0.1, 0.0}, per_scan);
  EXPECT_EQ(reject_outlier_scans(small, per_scan), 0u);
}

/// Appends `scans` scans of 40 pairs on a wall no other scan saw (plan y = 20, 5-9 m), the grid
/// through the same similarity as scans_of_pairs, moved by `shift`.
void append_unseen_scans(ReferencePairs& pairs, std::vector<std::size_t>& per_scan,
                         std::size_t scans, const Eigen::Vector2d& shift) {
  const double c = std::cos(0.2), s = std::sin(0.2);
  const Eigen::Index n = pairs.size();
  const auto added = static_cast<Eigen::Index>(40 * scans);
  pairs.points_in_plan.conservativeResize(2, n + added);
  pairs.points_in_grid.conservativeResize(2, n + added);
  for (Eigen::Index k = 0; k < added; ++k) {
    const Eigen::Vector2d p(5.0 + 0.1 * static_cast<double>(k % 40), 20.0);
    pairs.points_in_plan.col(n + k) = p;
    pairs.points_in_grid.col(n + k) = Eigen::Vector2d(2.0 + 1.05 * (c * p.x() - s * p.y()),
                                                      -1.0 + 1.05 * (s * p.x() + c * p.y())) +
                                      shift;
  }
  per_scan.insert(per_scan.end(), scans, 40);
}

TEST(OutlierScans, DropsScansGrosslyOffWhereNoOtherScanLooked) {
  std::vector<std::size_t> per_scan;
  // Three scans 3 m off, where no other scan saw the walls: no consensus, yet grossly off the
  // similarity of the rest (a filter lost along a corridor).
  ReferencePairs pairs = scans_of_pairs({}, Eigen::Vector2d::Zero(), per_scan);
  append_unseen_scans(pairs, per_scan, 3, {2.4, 1.8});
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 3u);
  EXPECT_EQ(pairs.size(), 2400);
  // 0.4 m off there is a bend the map may have: kept.
  pairs = scans_of_pairs({}, Eigen::Vector2d::Zero(), per_scan);
  append_unseen_scans(pairs, per_scan, 3, {0.4, 0.0});
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 0u);
  // Where more than a tenth of the pairs are that far off, the map is distorted: kept.
  pairs = scans_of_pairs({}, Eigen::Vector2d::Zero(), per_scan);
  append_unseen_scans(pairs, per_scan, 8, {2.4, 1.8});
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 0u);
  // A limit above the offset keeps them too.
  pairs = scans_of_pairs({}, Eigen::Vector2d::Zero(), per_scan);
  append_unseen_scans(pairs, per_scan, 3, {2.4, 1.8});
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan, {.max_gross_residual = 3.5}), 0u);
}

TEST(OutlierScans, ManyVisitsToEveryCellStillDropOnlyTheScansThatDisagree) {
  // A long run: the box driven round ten times, so each cell holds pairs of about 70 scans,
  // many of them each of the others' consensus. Scan 123 is 0.2 m off (beyond max_deviation),
  // scan 321 0.1 m (within it), scan 456 0.3 m the other way.
  std::vector<std::size_t> one_tour;
  const ReferencePairs tour = scans_of_pairs({}, Eigen::Vector2d::Zero(), one_tour);
  const Eigen::Index n = tour.size();
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 10 * n);
  pairs.points_in_grid.resize(2, 10 * n);
  Random random(9);
  for (Eigen::Index k = 0; k < 10 * n; ++k) {
    pairs.points_in_plan.col(k) = tour.points_in_plan.col(k % n);
    pairs.points_in_grid.col(k) =
        tour.points_in_grid.col(k % n) + Eigen::Vector2d(random.normal(0.01), random.normal(0.01));
  }
  const auto shift = [&](std::size_t scan, const Eigen::Vector2d& by) {
    for (Eigen::Index k = 0; k < 40; ++k)
      pairs.points_in_grid.col(static_cast<Eigen::Index>(40 * scan) + k) += by;
  };
  shift(123, {0.2, 0.0});
  shift(321, {0.0, 0.1});
  shift(456, {-0.3, 0.0});
  std::vector<std::size_t> per_scan(600, 40);
  EXPECT_EQ(reject_outlier_scans(pairs, per_scan), 2u);
  EXPECT_EQ(per_scan[123], 0u);
  EXPECT_EQ(per_scan[456], 0u);
  EXPECT_EQ(per_scan[321], 40u);
  EXPECT_EQ(pairs.size(), 598 * 40);
}

}  // namespace
}  // namespace floorgrid
