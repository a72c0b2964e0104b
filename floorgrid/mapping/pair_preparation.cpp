#include "floorgrid/mapping/pair_preparation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/mapping/pair_extent.hpp"

namespace floorgrid {

void validate_pairs(const ReferencePairs& pairs) {
  if (pairs.points_in_plan.cols() != pairs.points_in_grid.cols()) {
    throw InputError("plan and grid sides hold different numbers of points", {}, 0, "pairs");
  }
  if (pairs.has_weights() && pairs.weights.size() != pairs.size()) {
    throw InputError("the weights do not match the pairs in number", {}, 0, "pairs");
  }
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    if (!pairs.points_in_plan.col(i).allFinite() || !pairs.points_in_grid.col(i).allFinite()) {
      throw InputError("pair " + std::to_string(i + 1) + " has a coordinate that is not finite", {},
                       0, "pairs");
    }
    if (pairs.points_in_plan.col(i).cwiseAbs().maxCoeff() > kMaxCoordinate ||
        pairs.points_in_grid.col(i).cwiseAbs().maxCoeff() > kMaxCoordinate) {
      throw InputError("pair " + std::to_string(i + 1) +
                           " lies farther than 1e7 m from the origin: not a physical coordinate",
                       {}, 0, "pairs");
    }
    if (pairs.has_weights() && !(std::isfinite(pairs.weights[i]) && pairs.weights[i] >= 0.0)) {
      throw InputError(
          "pair " + std::to_string(i + 1) + " has a weight that is not finite and >= 0", {}, 0,
          "pairs");
    }
  }
  if (pairs.has_weights() && pairs.size() > 0 && !(pairs.weights.sum() > 0.0))
    throw InputError("every weight is 0: no pair would count", {}, 0, "pairs");
}

ReferencePairs merge_duplicates(const ReferencePairs& pairs, DuplicateMerge* report) {
  // Sort indices by plan point; equal plan points become neighbours.
  const Eigen::Index n = pairs.size();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    order[static_cast<std::size_t>(i)] = i;
  const auto& p = pairs.points_in_plan;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    if (p(0, a) != p(0, b))
      return p(0, a) < p(0, b);
    if (p(1, a) != p(1, b))
      return p(1, a) < p(1, b);
    return a < b;
  });
  std::vector<std::vector<Eigen::Index>> groups;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Index i = order[k];
    if (k > 0 && p.col(i) == p.col(order[k - 1])) {
      groups.back().push_back(i);
    } else {
      groups.push_back({i});
    }
  }
  DuplicateMerge merge;
  if (groups.size() == static_cast<std::size_t>(n)) {
    if (report != nullptr)
      *report = merge;
    return pairs;
  }
  // Keep the first occurrence's place in the input order, so the result is deterministic.
  std::sort(groups.begin(), groups.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
  std::vector<Eigen::Index> firsts;
  for (const auto& g : groups)
    firsts.push_back(g.front());
  ReferencePairs out = select_pairs(pairs, firsts);
  if (!out.has_weights())
    out.weights = Eigen::VectorXd::Ones(out.size());
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const auto& members = groups[k];
    if (members.size() == 1)
      continue;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    double weight = 0.0;
    for (const Eigen::Index i : members) {
      sum += pairs.weight(i) * pairs.points_in_grid.col(i);
      weight += pairs.weight(i);
    }
    const auto col = static_cast<Eigen::Index>(k);
    if (weight > 0.0)
      out.points_in_grid.col(col) = sum / weight;
    out.weights[col] = weight;
    merge.merged += members.size() - 1;
    double spread = 0.0;
    for (const Eigen::Index i : members) {
      spread = std::max(spread, (pairs.points_in_grid.col(i) - out.points_in_grid.col(col)).norm());
    }
    if (spread > 0.01)
      ++merge.conflicting;
    merge.largest_conflict = std::max(merge.largest_conflict, 2.0 * spread);
  }
  if (report != nullptr)
    *report = merge;
  return out;
}

namespace {

/// A square cell's column and row.
using CellKey = std::pair<std::int64_t, std::int64_t>;

/// The cell index of `offset` metres from the origin, clamped far inside the int64 range: a
/// far pair with tiny cells must not overflow (it lands in a cell of its own either way).
std::int64_t cell_index(double offset, double cell) {
  return static_cast<std::int64_t>(std::clamp(std::floor(offset / cell), -4e18, 4e18));
}

/// Per pair, its square cell of side `cell` over the plan points, from `origin`.
std::vector<CellKey> bin(const ReferencePairs& pairs, const Eigen::Vector2d& origin, double cell) {
  std::vector<CellKey> keys(static_cast<std::size_t>(pairs.size()));
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    keys[static_cast<std::size_t>(i)] = {cell_index(pairs.points_in_plan(1, i) - origin.y(), cell),
                                         cell_index(pairs.points_in_plan(0, i) - origin.x(), cell)};
  }
  return keys;
}

/// How many distinct cells hold pairs.
std::size_t count_cells(std::vector<CellKey> keys) {
  std::sort(keys.begin(), keys.end());
  return static_cast<std::size_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

}  // namespace

ReferencePairs reduce_pairs(const ReferencePairs& pairs, const ReductionOptions& options,
                            ReductionSummary* summary) {
  ReductionSummary s;
  s.pairs_before = static_cast<std::size_t>(pairs.size());
  s.pairs_after = s.pairs_before;
  if (options.budget < 3)
    throw InputError("must be >= 3", {}, 0, "reduction.budget");
  if (s.pairs_before <= options.budget) {
    if (summary != nullptr)
      *summary = s;
    return pairs;
  }
  const Eigen::Vector2d lo = pairs.points_in_plan.rowwise().minCoeff();
  const Eigen::Vector2d hi = pairs.points_in_plan.rowwise().maxCoeff();
  const double extent = std::max((hi - lo).maxCoeff(), 1e-9);
  // The smallest cells searched come from the bulk's extent when a few far pairs stretch the
  // full one (one pair at 1e6 m beside a 100 m building made 1 km cells: two pairs left); as
  // before otherwise, so that pairs without far ones are reduced exactly as they were.
  const double bulk = std::max(robust_extent(pairs.points_in_plan), 1e-9);
  const double searched = extent > 10.0 * bulk ? bulk : extent;
  // Bisect on the cell size (in log space) for the smallest cells within the budget; one cell
  // of the full extent holds every pair.
  double small = searched / std::sqrt(static_cast<double>(s.pairs_before)) / 4.0,
         large = extent * 1.01;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double mid = std::sqrt(small * large);
    if (count_cells(bin(pairs, lo, mid)) > options.budget) {
      small = mid;
    } else {
      large = mid;
    }
    if (large / small < 1.01)
      break;
  }
  // Group the pairs by cell: sort their indices by cell key.
  const std::vector<CellKey> key = bin(pairs, lo, large);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(pairs.size()));
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)];
  });
  std::vector<std::vector<Eigen::Index>> cells;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const CellKey& cell = key[static_cast<std::size_t>(order[k])];
    if (k == 0 || cell != key[static_cast<std::size_t>(order[k - 1])])
      cells.emplace_back();
    cells.back().push_back(order[k]);
  }
  ReferencePairs out;
  out.points_in_plan.resize(2, static_cast<Eigen::Index>(cells.size()));
  out.points_in_grid.resize(2, static_cast<Eigen::Index>(cells.size()));
  out.weights.resize(static_cast<Eigen::Index>(cells.size()));
  Eigen::Index k = 0;
  for (const auto& members : cells) {
    // A robust cell mean: pairs whose displacement agrees with the cell's median displacement.
    std::vector<double> dx, dy;
    for (const Eigen::Index i : members) {
      dx.push_back(pairs.points_in_grid(0, i) - pairs.points_in_plan(0, i));
      dy.push_back(pairs.points_in_grid(1, i) - pairs.points_in_plan(1, i));
    }
    const double mx = median(dx), my = median(dy);
    std::vector<double> deviation;
    for (std::size_t j = 0; j < members.size(); ++j)
      deviation.push_back(std::hypot(dx[j] - mx, dy[j] - my));
    const double limit = std::max(3.0 * 1.4826 * median(deviation), 0.02);
    Eigen::Vector2d plan_sum = Eigen::Vector2d::Zero(), grid_sum = Eigen::Vector2d::Zero();
    double weight = 0.0;
    for (std::size_t j = 0; j < members.size(); ++j) {
      if (deviation[j] > limit)
        continue;
      const Eigen::Index i = members[j];
      const double w = std::max(pairs.weight(i), 1e-12);
      plan_sum += w * pairs.points_in_plan.col(i);
      grid_sum += w * pairs.points_in_grid.col(i);
      weight += w;
    }
    out.points_in_plan.col(k) = plan_sum / weight;
    out.points_in_grid.col(k) = grid_sum / weight;
    out.weights[k] = weight;
    ++k;
  }
  s.applied = true;
  s.pairs_after = cells.size();
  s.cell_size = large;
  if (summary != nullptr)
    *summary = s;
  return out;
}

ReferencePairs thin_in_order(const ReferencePairs& pairs, std::size_t budget) {
  const auto n = static_cast<std::size_t>(pairs.size());
  if (n <= budget || budget == 0)
    return pairs;
  std::vector<Eigen::Index> kept(budget);
  for (std::size_t k = 0; k < budget; ++k)
    kept[k] = static_cast<Eigen::Index>(k * n / budget);
  return select_pairs(pairs, kept);
}

double plan_extent(const ReferencePairs& pairs) {
  if (pairs.empty())
    return 0.0;
  return (pairs.points_in_plan.rowwise().maxCoeff() - pairs.points_in_plan.rowwise().minCoeff())
      .norm();
}

bool plan_points_collinear(const ReferencePairs& pairs, double tolerance) {
  const Eigen::Index n = pairs.size();
  if (n < 3)
    return true;
  const double extent = plan_extent(pairs);
  if (extent == 0.0)
    return true;
  // The farthest pair of a few candidates spans a line; collinear when no point is off it.
  const Eigen::Vector2d a = pairs.points_in_plan.col(0);
  Eigen::Index far = 0;
  for (Eigen::Index i = 1; i < n; ++i) {
    if ((pairs.points_in_plan.col(i) - a).squaredNorm() >
        (pairs.points_in_plan.col(far) - a).squaredNorm())
      far = i;
  }
  const Eigen::Vector2d d = (pairs.points_in_plan.col(far) - a).normalized();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d v = pairs.points_in_plan.col(i) - a;
    if (std::abs(d.x() * v.y() - d.y() * v.x()) > tolerance * extent)
      return false;
  }
  return true;
}

std::size_t distinct_plan_points(const ReferencePairs& pairs) {
  std::vector<std::pair<double, double>> points;
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    points.emplace_back(pairs.points_in_plan(0, i), pairs.points_in_plan(1, i));
  std::sort(points.begin(), points.end());
  return static_cast<std::size_t>(std::unique(points.begin(), points.end()) - points.begin());
}

}  // namespace floorgrid
