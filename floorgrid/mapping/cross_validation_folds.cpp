#include "floorgrid/mapping/cross_validation_folds.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <utility>

#include "floorgrid/core/random.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/point_index.hpp"

namespace floorgrid {

namespace {

/// 0..n-1 in an order shuffled by `random` (Fisher-Yates from the back).
std::vector<std::size_t> shuffled_indices(std::size_t n, Random& random) {
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  for (std::size_t i = n; i > 1; --i) {
    std::swap(order[i - 1],
              order[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  }
  return order;
}

using BlockKey = std::pair<std::int64_t, std::int64_t>;

/// The block (column, row) of every point, blocks of `size` metres from the points' lower left.
std::vector<BlockKey> block_keys(const Eigen::Matrix2Xd& points, double size) {
  std::vector<BlockKey> keys(static_cast<std::size_t>(points.cols()));
  if (points.cols() == 0)
    return keys;
  const Eigen::Vector2d lower = points.rowwise().minCoeff();
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::Vector2d cell = ((points.col(i) - lower) / size).array().floor();
    keys[static_cast<std::size_t>(i)] = {static_cast<std::int64_t>(cell.x()),
                                         static_cast<std::int64_t>(cell.y())};
  }
  return keys;
}

std::size_t occupied_blocks(const Eigen::Matrix2Xd& points, double size) {
  std::vector<BlockKey> keys = block_keys(points, size);
  std::sort(keys.begin(), keys.end());
  return static_cast<std::size_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

/// Median distance from a point to its nearest other point, metres (0 for fewer than 2).
double median_neighbour_distance(const Eigen::Matrix2Xd& points) {
  if (points.cols() < 2)
    return 0.0;
  const PointIndex2D index(points);
  std::vector<double> distances;
  distances.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    distances.push_back(index.nearest_k(points.col(i), 2).back().distance);
  return upper_median(distances);
}

}  // namespace

Folds random_folds(std::size_t n, std::size_t folds, std::uint64_t seed) {
  assert(folds >= 1);
  Folds result;
  result.count = std::min(folds, n);
  result.fold_of.resize(n);
  Random random(seed);
  result.order = shuffled_indices(n, random);
  for (std::size_t i = 0; i < n; ++i)
    result.fold_of[result.order[i]] = i % result.count;
  return result;
}

Folds blocked_folds(const Eigen::Matrix2Xd& points, std::size_t folds, double block_size,
                    std::uint64_t seed) {
  assert(folds >= 1 && block_size > 0.0);
  const auto n = static_cast<std::size_t>(points.cols());
  Folds result;
  result.block_size = block_size;
  const std::vector<BlockKey> keys = block_keys(points, block_size);
  // Blocks numbered in (column, row) order, so the numbering does not depend on the pairs' order.
  std::map<BlockKey, std::size_t> block_ids;
  for (const BlockKey& key : keys)
    block_ids.emplace(key, 0);
  std::size_t next = 0;
  for (auto& [key, id] : block_ids)
    id = next++;
  result.blocks = block_ids.size();
  result.block_of.resize(n);
  std::vector<std::size_t> block_sizes(result.blocks, 0);
  for (std::size_t i = 0; i < n; ++i) {
    result.block_of[i] = block_ids.at(keys[i]);
    ++block_sizes[result.block_of[i]];
  }
  result.count = std::min(folds, result.blocks);
  result.fold_of.resize(n);
  result.order.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    result.order[i] = i;
  if (result.count == 0)
    return result;
  // Whole blocks, in a seeded order, each to the lightest fold: folds of similar size whatever
  // the blocks' sizes, and the same folds for the same seed.
  Random random(seed);
  const std::vector<std::size_t> order = shuffled_indices(result.blocks, random);
  std::vector<std::size_t> fold_of_block(result.blocks, 0);
  std::vector<std::size_t> fold_sizes(result.count, 0);
  for (const std::size_t block : order) {
    const auto lightest = static_cast<std::size_t>(
        std::min_element(fold_sizes.begin(), fold_sizes.end()) - fold_sizes.begin());
    fold_of_block[block] = lightest;
    fold_sizes[lightest] += block_sizes[block];
  }
  for (std::size_t i = 0; i < n; ++i)
    result.fold_of[i] = fold_of_block[result.block_of[i]];
  return result;
}

Folds run_folds(std::size_t n, std::size_t folds, std::size_t runs_per_fold) {
  assert(folds >= 1 && runs_per_fold >= 1);
  Folds result;
  result.count = std::min(folds, n);
  result.fold_of.resize(n);
  result.order.resize(n);
  const std::size_t runs = result.count * runs_per_fold;
  for (std::size_t i = 0; i < n; ++i) {
    result.order[i] = i;
    result.fold_of[i] = run_stretch(i, n, runs) % result.count;
  }
  return result;
}

double choose_block_size(const Eigen::Matrix2Xd& points, std::size_t folds) {
  const double smallest = 2.0 * median_neighbour_distance(points);
  const std::size_t wanted = kAutoBlocksPerFold * std::max<std::size_t>(folds, 1);
  double size = kLargestAutoBlock;
  while (occupied_blocks(points, size) < wanted && 0.8 * size >= smallest && size > 1e-6)
    size *= 0.8;
  return size;
}

void Folds::split(std::size_t fold, std::vector<Eigen::Index>& train,
                  std::vector<Eigen::Index>& test) const {
  train.clear();
  test.clear();
  const auto add = [&](std::size_t i) {
    (fold_of[i] == fold ? test : train).push_back(static_cast<Eigen::Index>(i));
  };
  if (order.empty()) {
    for (std::size_t i = 0; i < fold_of.size(); ++i)
      add(i);
  } else {
    for (const std::size_t i : order)
      add(i);
  }
}

}  // namespace floorgrid
