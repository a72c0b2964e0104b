#include "floorgrid/mapping/local_transforms.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

namespace {

/// A cluster while it is built: member pair indices and its transform.
struct Growing {
  std::vector<Eigen::Index> members;
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

Eigen::Vector2d apply(const Eigen::Matrix3d& T, const Eigen::Vector2d& p) {
  return T.topLeftCorner<2, 2>() * p + T.topRightCorner<2, 1>();
}

double error(const Eigen::Matrix3d& T, const ReferencePairs& pairs, Eigen::Index i) {
  return (apply(T, pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
}

/// Least-squares transform of a set of pairs, or nullopt when they determine none.
std::optional<TransformEstimate> fit_members(const ReferencePairs& pairs,
                                             const std::vector<Eigen::Index>& members,
                                             TransformKind kind) {
  const ReferencePairs subset = select_pairs(pairs, members);
  TransformEstimationOptions options;
  options.kind = kind;
  PairMoments moments;
  moments.origin_in_plan = subset.points_in_plan.col(0);
  moments.origin_in_grid = subset.points_in_grid.col(0);
  for (Eigen::Index i = 0; i < subset.size(); ++i) {
    moments.add(subset.points_in_plan.col(i), subset.points_in_grid.col(i), subset.weight(i));
  }
  return fit_transform(moments, options);
}

Eigen::Vector2d centroid_of(const ReferencePairs& pairs, const std::vector<Eigen::Index>& members) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Index i : members)
    sum += pairs.points_in_plan.col(i);
  return sum / static_cast<double>(members.size());
}

/// Algorithm 1, lines 1-16, for one cell: clusters grown around the best of several seeded
/// minimal samples, each taking every remaining pair that agrees with it.
void cluster_cell(const ReferencePairs& pairs, std::vector<Eigen::Index> remaining,
                  const LocalTransformsOptions& options, Random& random,
                  std::vector<Growing>& out) {
  const int sample = minimal_sample_size(options.kind);
  while (static_cast<int>(remaining.size()) >= std::max(sample, options.min_cluster_pairs)) {
    std::vector<Eigen::Index> best;
    Eigen::Matrix3d best_T = Eigen::Matrix3d::Identity();
    for (int h = 0; h < options.hypotheses; ++h) {
      std::vector<Eigen::Index> seed;
      for (int k = 0; k < sample; ++k) {
        seed.push_back(remaining[static_cast<std::size_t>(
            random.integer(0, static_cast<std::int64_t>(remaining.size()) - 1))]);
      }
      const auto estimate = fit_members(pairs, seed, options.kind);
      if (!estimate)
        continue;
      std::vector<Eigen::Index> agree;
      for (const Eigen::Index i : remaining) {
        if (error(estimate->T_grid_plan, pairs, i) <= options.agreement)
          agree.push_back(i);
      }
      if (agree.size() > best.size()) {
        best = agree;
        best_T = estimate->T_grid_plan;
      }
    }
    if (static_cast<int>(best.size()) < options.min_cluster_pairs)
      break;
    // Refit on the members and take the pairs that agree with the refit.
    if (const auto refit = fit_members(pairs, best, options.kind)) {
      best_T = refit->T_grid_plan;
      std::vector<Eigen::Index> agree;
      for (const Eigen::Index i : remaining) {
        if (error(best_T, pairs, i) <= options.agreement)
          agree.push_back(i);
      }
      if (agree.size() >= best.size())
        best = agree;
    }
    Growing cluster;
    cluster.members = best;
    cluster.T = best_T;
    cluster.centroid = centroid_of(pairs, best);
    out.push_back(cluster);
    std::vector<Eigen::Index> left;
    std::sort(best.begin(), best.end());
    std::set_difference(remaining.begin(), remaining.end(), best.begin(), best.end(),
                        std::back_inserter(left));
    remaining = left;
  }
}

/// Whether two clusters' transforms agree on each other's pairs (rms within the agreement).
bool compatible(const ReferencePairs& pairs, const Growing& a, const Growing& b, double agreement) {
  const auto rms = [&](const Eigen::Matrix3d& T, const std::vector<Eigen::Index>& members) {
    double sum = 0.0;
    for (const Eigen::Index i : members)
      sum += std::pow(error(T, pairs, i), 2);
    return std::sqrt(sum / static_cast<double>(members.size()));
  };
  return rms(a.T, b.members) <= agreement && rms(b.T, a.members) <= agreement;
}

}  // namespace

LocalTransformsMapping::LocalTransformsMapping(MappingCommonOptions common,
                                               LocalTransformsOptions options)
    : PointMapping(std::move(common)), options_(options) {
  if (!(options_.agreement > 0.0))
    throw InputError("must be > 0", {}, 0, "ct.agreement");
  if (options_.levels < 0)
    throw InputError("must be >= 0", {}, 0, "ct.levels");
  if (options_.min_cluster_pairs < minimal_sample_size(options_.kind)) {
    throw InputError("must be at least the minimal sample size", {}, 0, "ct.min_cluster_pairs");
  }
  if (!(options_.weight_power > 0.0))
    throw InputError("must be > 0", {}, 0, "ct.weight_power");
}

void LocalTransformsMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  Random random(common().seed);
  const Eigen::Vector2d lo = pairs.points_in_plan.rowwise().minCoeff();
  const double cell =
      options_.cell_size > 0.0 ? options_.cell_size : std::max(plan_extent(pairs) / 12.0, 1e-6);
  // Level 0: clusters per cell.
  std::map<std::pair<long, long>, std::vector<Eigen::Index>> cells;
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector2d c = (pairs.points_in_plan.col(i) - lo) / cell;
    cells[{static_cast<long>(std::floor(c.x())), static_cast<long>(std::floor(c.y()))}].push_back(
        i);
  }
  std::vector<Growing> clusters;
  for (const auto& [key, members] : cells)
    cluster_cell(pairs, members, options_, random, clusters);
  if (clusters.empty()) {
    // Too few pairs per cell for any cluster: one cluster over everything.
    std::vector<Eigen::Index> all(static_cast<std::size_t>(pairs.size()));
    for (Eigen::Index i = 0; i < pairs.size(); ++i)
      all[static_cast<std::size_t>(i)] = i;
    LocalTransformsOptions loose = options_;
    loose.min_cluster_pairs = minimal_sample_size(options_.kind);
    loose.agreement = std::max(options_.agreement, 1e-3 * plan_extent(pairs)) * 10.0;
    cluster_cell(pairs, all, loose, random, clusters);
    if (clusters.empty())
      throw InputError("no local transform fits the pairs", {}, 0, "pairs");
    summary.warnings.push_back("too few pairs per cell: one cluster over all pairs");
  }
  // Algorithm 1, lines 17-21, repeated on coarser grids: neighbouring clusters with agreeing
  // transforms merge.
  for (int level = 0; level <= options_.levels; ++level) {
    const double size = cell * std::pow(2.0, level);
    bool merged = true;
    while (merged) {
      merged = false;
      for (std::size_t a = 0; a < clusters.size() && !merged; ++a) {
        for (std::size_t b = a + 1; b < clusters.size() && !merged; ++b) {
          const Eigen::Vector2d d = (clusters[a].centroid - clusters[b].centroid).cwiseAbs();
          if (d.maxCoeff() > 1.5 * size)
            continue;  // not neighbours at this level
          if (!compatible(pairs, clusters[a], clusters[b], options_.agreement))
            continue;
          std::vector<Eigen::Index> members = clusters[a].members;
          members.insert(members.end(), clusters[b].members.begin(), clusters[b].members.end());
          const auto refit = fit_members(pairs, members, options_.kind);
          if (!refit)
            continue;
          clusters[a].members = members;
          clusters[a].T = refit->T_grid_plan;
          clusters[a].centroid = centroid_of(pairs, members);
          clusters.erase(clusters.begin() + static_cast<std::ptrdiff_t>(b));
          merged = true;
        }
      }
    }
  }
  clusters_.clear();
  double sum_sq = 0.0;
  std::size_t clustered = 0;
  for (const Growing& g : clusters) {
    Cluster c;
    c.T_grid_plan = g.T;
    c.centroid = g.centroid;
    c.pairs = g.members.size();
    double s = 0.0;
    for (const Eigen::Index i : g.members)
      s += std::pow(error(g.T, pairs, i), 2);
    c.rms = std::sqrt(s / static_cast<double>(g.members.size()));
    sum_sq += s;
    clustered += g.members.size();
    clusters_.push_back(c);
  }
  summary.rms_m = std::sqrt(sum_sq / static_cast<double>(clustered));
  summary.details = {{"clusters", clusters_.size()},
                     {"clustered_pairs", clustered},
                     {"unclustered_pairs", static_cast<std::size_t>(pairs.size()) - clustered},
                     {"cell_size_m", cell},
                     {"levels", options_.levels},
                     {"weight_power", options_.weight_power}};
}

Eigen::Vector2d LocalTransformsMapping::forward(const Eigen::Vector2d& p) const {
  // Algorithm 2: weights 1/d^power, normalized; a point on a centroid takes that cluster.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double total = 0.0;
  const bool squared = options_.weight_power == 2.0;  // the default: no pow() per cluster
  for (const Cluster& c : clusters_) {
    const double d2 = (p - c.centroid).squaredNorm();
    if (d2 < 1e-24)
      return apply(c.T_grid_plan, p);
    const double w = squared ? 1.0 / d2 : std::pow(d2, -0.5 * options_.weight_power);
    sum += w * apply(c.T_grid_plan, p);
    total += w;
  }
  return sum / total;
}

Eigen::Matrix2d LocalTransformsMapping::jacobian(const Eigen::Vector2d& p) const {
  // q = sum_k w_k T_k p / sum_k w_k: dq/dp = sum_k w_k A_k / W + sum_k (T_k p - q) grad(w_k)^T / W.
  const Eigen::Vector2d q = forward(p);
  Eigen::Matrix2d j = Eigen::Matrix2d::Zero();
  double total = 0.0;
  for (const Cluster& c : clusters_) {
    const Eigen::Vector2d r = p - c.centroid;
    const double d = r.norm();
    if (d < 1e-12)
      return c.T_grid_plan.topLeftCorner<2, 2>();
    const double w = std::pow(d, -options_.weight_power);
    const Eigen::Vector2d grad = -options_.weight_power * w / (d * d) * r;
    j += w * c.T_grid_plan.topLeftCorner<2, 2>() + (apply(c.T_grid_plan, p) - q) * grad.transpose();
    total += w;
  }
  return j / total;
}

Value LocalTransformsMapping::parameters() const {
  Value clusters = Value::array();
  for (const Cluster& c : clusters_) {
    clusters.push_back({{"T_grid_plan", model_fields::matrix(c.T_grid_plan)},
                        {"centroid", Value::array({c.centroid.x(), c.centroid.y()})},
                        {"pairs", c.pairs},
                        {"rms_m", c.rms}});
  }
  return {{"kind", transform_kind_name(options_.kind)},
          {"weight_power", options_.weight_power},
          {"agreement_m", options_.agreement},
          {"clusters", clusters}};
}

void LocalTransformsMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  const std::string p = "parameters.";
  options_.weight_power =
      number(member(j, "weight_power", where, p), where, p + "weight_power", 0.1, 16.0);
  const Value& list = member(j, "clusters", where, p);
  if (!list.is_array() || list.size() == 0 || list.size() > kMaxPoints)
    throw InputError("expected a non-empty list", where, 0, p + "clusters");
  clusters_.clear();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = p + "clusters[" + std::to_string(i) + "].";
    const Value& item = list.items()[i];
    Cluster c;
    c.T_grid_plan =
        matrix(member(item, "T_grid_plan", where, field), where, field + "T_grid_plan", 3, 3);
    const Eigen::Matrix2Xd centroid =
        points(Value::array({member(item, "centroid", where, field)}), where, field + "centroid");
    c.centroid = centroid.col(0);
    if (const Value* pairs = optional_member(item, "pairs"))
      c.pairs = static_cast<std::size_t>(integer(*pairs, where, field + "pairs", 0, INT64_MAX));
    if (const Value* rms = optional_member(item, "rms_m"))
      c.rms = number(*rms, where, field + "rms_m");
    clusters_.push_back(c);
  }
}

}  // namespace floorgrid
