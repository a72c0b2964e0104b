#include "floorgrid/geometry/ransac.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/inlier_classification.hpp"
#include "floorgrid/geometry/residual_scale.hpp"

namespace floorgrid {
namespace {

using Affine = Eigen::Matrix<double, 2, 3>;  // [L | t]: q = L p + t

// Passes of the refit on the verification subset at most.
constexpr int kSubsetRefitPasses = 10;
// Adaptive threshold: rounds of refit and re-estimated noise at most, the relative change of
// the threshold that ends them, and its floor as a share of the extent (exact pairs have no
// noise to measure; below this only rounding is left).
constexpr int kMaxScalePasses = 20;
constexpr double kScaleTolerance = 0.01;
constexpr double kMinThresholdFraction = 1e-6;

[[noreturn]] void throw_pairs_error(const std::string& message) {
  throw InputError(message, {}, 0, "pairs");
}

void validate_options(const RansacOptions& o) {
  if (o.inlier_threshold) {
    require_option(*o.inlier_threshold > 0.0 && std::isfinite(*o.inlier_threshold), "ransac",
                   "inlier_threshold", *o.inlier_threshold, "> 0 metres, or unset (adaptive)");
  }
  require_option(o.threshold_sigmas > 0.0 && o.threshold_sigmas <= 100.0, "ransac",
                 "threshold_sigmas", o.threshold_sigmas, "in (0, 100]");
  require_option(o.search_threshold_fraction > 0.0 && o.search_threshold_fraction <= 1.0, "ransac",
                 "search_threshold_fraction", o.search_threshold_fraction, "in (0, 1]");
  require_option(o.confidence > 0.0 && o.confidence < 1.0, "ransac", "confidence", o.confidence,
                 "in (0, 1)");
  require_option(o.max_iterations >= 1, "ransac", "max_iterations", o.max_iterations, ">= 1");
  require_option(o.min_iterations >= 0 && o.min_iterations <= o.max_iterations, "ransac",
                 "min_iterations", o.min_iterations, "in [0, max_iterations]");
  require_option(o.preemptive_subset >= 1, "ransac", "preemptive_subset", o.preemptive_subset,
                 ">= 1");
  require_option(o.verify_count >= 1, "ransac", "verify_count", o.verify_count, ">= 1");
  require_option(o.verify_subset >= 1, "ransac", "verify_subset", o.verify_subset, ">= 1");
  require_option(o.max_refit_passes >= 1, "ransac", "max_refit_passes", o.max_refit_passes, ">= 1");
  require_option(o.min_sample_separation >= 0.0 && o.min_sample_separation < 1.0, "ransac",
                 "min_sample_separation", o.min_sample_separation, "in [0, 1)");
  require_option(o.threads == 1 || o.threads == 2, "ransac", "threads", o.threads, "1 or 2");
}

void validate_pair(const ReferencePairs& pairs, Eigen::Index i) {
  if (!pairs.points_in_plan.col(i).allFinite() || !pairs.points_in_grid.col(i).allFinite()) {
    throw_pairs_error("pair " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
  const double w = pairs.weight(i);
  if (!(w >= 0.0) || !(w <= DBL_MAX)) {
    throw_pairs_error("pair " + std::to_string(i) + " has a negative, NaN or infinite weight");
  }
}

// ---- the preemptive scoring subset, as contiguous arrays about fixed origins ----

struct ScoringSet {
  Eigen::Vector2d origin_in_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d origin_in_grid = Eigen::Vector2d::Zero();
  Eigen::ArrayXd px, py, qx, qy, w;  // relative to the origins
  double extent = 0.0;               // metres: bounding box diagonal of the plan points
  double grid_extent = 0.0;          // metres: diagonal of the grid points' 5-95% box
};

// The spread of `values` between their 5th and 95th percentiles: an extent that a few wild
// outliers do not stretch.
double percentile_spread(const Eigen::ArrayXd& values) {
  std::vector<double> v(values.begin(), values.end());
  const auto last = static_cast<double>(v.size() - 1);
  const auto lo = v.begin() + static_cast<std::ptrdiff_t>(std::floor(0.05 * last));
  const auto hi = v.begin() + static_cast<std::ptrdiff_t>(std::ceil(0.95 * last));
  std::nth_element(v.begin(), hi, v.end());
  std::nth_element(v.begin(), lo, hi);
  return *hi - *lo;
}

// `count` pairs drawn at random, one from each of `count` equal strata of the pair indices
// (sorted and distinct by construction, no sort needed, and spread over the whole recording),
// or all pairs when there are fewer.
std::vector<Eigen::Index> draw_subset(Eigen::Index n, std::size_t count, Random& random) {
  std::vector<Eigen::Index> indices;
  if (static_cast<std::size_t>(n) <= count) {
    indices.resize(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i)
      indices[static_cast<std::size_t>(i)] = i;
    return indices;
  }
  indices.resize(count);
  const double stratum = static_cast<double>(n) / static_cast<double>(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto first = static_cast<Eigen::Index>(std::ceil(stratum * static_cast<double>(k)));
    const auto last = static_cast<Eigen::Index>(std::ceil(stratum * static_cast<double>(k + 1)));
    indices[k] = std::min(n - 1, first + static_cast<Eigen::Index>(
                                             random.uniform() * static_cast<double>(last - first)));
  }
  return indices;
}

ScoringSet make_scoring_set(const ReferencePairs& pairs, const std::vector<Eigen::Index>& indices) {
  const auto m = static_cast<Eigen::Index>(indices.size());
  ScoringSet s;
  s.px.resize(m), s.py.resize(m), s.qx.resize(m), s.qy.resize(m), s.w.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Index i = indices[static_cast<std::size_t>(k)];
    validate_pair(pairs, i);
    s.px[k] = pairs.points_in_plan(0, i), s.py[k] = pairs.points_in_plan(1, i);
    s.qx[k] = pairs.points_in_grid(0, i), s.qy[k] = pairs.points_in_grid(1, i);
    s.w[k] = pairs.weight(i);
  }
  s.origin_in_plan = {s.px.mean(), s.py.mean()};
  s.origin_in_grid = {s.qx.mean(), s.qy.mean()};
  s.px -= s.origin_in_plan.x(), s.py -= s.origin_in_plan.y();
  s.qx -= s.origin_in_grid.x(), s.qy -= s.origin_in_grid.y();
  s.extent = std::hypot(s.px.maxCoeff() - s.px.minCoeff(), s.py.maxCoeff() - s.py.minCoeff());
  s.grid_extent = std::hypot(percentile_spread(s.qx), percentile_spread(s.qy));
  return s;
}

ReferencePairs gather_pairs(const ReferencePairs& pairs, const std::vector<Eigen::Index>& indices) {
  for (const Eigen::Index i : indices)
    validate_pair(pairs, i);  // here, where the pair's own index is known
  return select_pairs(pairs, indices);
}

// T expressed about the origins: q - o_G = L (p - o_F) + t'.
Affine relative_to(const Affine& T, const Eigen::Vector2d& o_plan, const Eigen::Vector2d& o_grid) {
  Affine r = T;
  r.col(2) = T.leftCols<2>() * o_plan + T.col(2) - o_grid;
  return r;
}

struct Score {
  double cost = 0.0;        // MSAC: sum w min(d^2, threshold^2)
  std::size_t inliers = 0;  // d <= threshold, unweighted
};

Score score_hypothesis(const ScoringSet& s, const Affine& T, double threshold2) {
  const Affine r = relative_to(T, s.origin_in_plan, s.origin_in_grid);
  const auto d2 = (r(0, 0) * s.px + r(0, 1) * s.py + r(0, 2) - s.qx).square() +
                  (r(1, 0) * s.px + r(1, 1) * s.py + r(1, 2) - s.qy).square();
  Score score;
  score.cost = (s.w * d2.min(threshold2)).sum();
  score.inliers = static_cast<std::size_t>((d2 <= threshold2).count());
  return score;
}

// ---- hypotheses ----

struct Hypothesis {
  Affine T;
  bool mirrored = false;
  Score score;
};

TransformEstimationOptions fit_options(TransformKind kind, bool mirrored) {
  return {kind, mirrored ? Reflection::require : Reflection::forbid};
}

// The minimal sample's hypotheses (a proper and, when allowed, a mirrored one), or none when
// the sample is degenerate: plan points closer than `separation`, or (affine) a triangle whose
// height is below it.
std::vector<Hypothesis> hypotheses_from_sample(const ReferencePairs& pairs,
                                               const Eigen::Index* sample,
                                               const RansacOptions& options, double separation) {
  const int size = minimal_sample_size(options.kind);
  PairMoments moments;
  moments.origin_in_plan = pairs.points_in_plan.col(sample[0]);
  moments.origin_in_grid = pairs.points_in_grid.col(sample[0]);
  for (int k = 0; k < size; ++k) {
    const Eigen::Vector2d p = pairs.points_in_plan.col(sample[k]);
    if (!p.allFinite() || !pairs.points_in_grid.col(sample[k]).allFinite())
      return {};
    for (int j = 0; j < k; ++j) {
      if ((p - pairs.points_in_plan.col(sample[j])).norm() < separation)
        return {};
    }
    moments.add(p, pairs.points_in_grid.col(sample[k]));
  }
  if (size == 3) {
    const Eigen::Vector2d a = pairs.points_in_plan.col(sample[1]) - moments.origin_in_plan;
    const Eigen::Vector2d b = pairs.points_in_plan.col(sample[2]) - moments.origin_in_plan;
    const double longest = std::max({a.norm(), b.norm(), (a - b).norm()});
    const double height = std::abs(a.x() * b.y() - a.y() * b.x()) / longest;
    if (!(height >= separation) || !(height > 0.0))
      return {};
  }
  std::vector<Hypothesis> out;
  const bool affine = options.kind == TransformKind::affine;
  for (const bool mirrored : {false, true}) {
    if (!affine && ((mirrored && options.reflection == Reflection::forbid) ||
                    (!mirrored && options.reflection == Reflection::require))) {
      continue;
    }
    if (affine && mirrored)
      break;
    const std::optional<TransformEstimate> e =
        fit_transform(moments, fit_options(options.kind, mirrored));
    if (!e || !(e->scale > 0.0) || !e->T_grid_plan.allFinite())
      continue;
    out.push_back({e->T_grid_plan.topRows<2>(), affine ? e->reflected : mirrored, {}});
  }
  return out;
}

void keep_best(std::vector<Hypothesis>& best, const Hypothesis& h, std::size_t count) {
  // Strictly better only: on a tie the earlier (and for one sample, the proper) one stays.
  const auto at =
      std::upper_bound(best.begin(), best.end(), h.score.cost,
                       [](double cost, const Hypothesis& b) { return cost < b.score.cost; });
  if (static_cast<std::size_t>(at - best.begin()) >= count)
    return;
  best.insert(at, h);
  if (best.size() > count)
    best.pop_back();
}

// ---- refit: classify, refit on the inliers, until the inliers are stable ----

struct Refined {
  Hypothesis hypothesis;
  InlierPass last;  // the classification under hypothesis.T (moments: the last change)
  double inlier_weight = 0.0;
  int passes = 0;
  bool stable = false;
  std::string note;
};

Refined refit_on_inliers(const ReferencePairs& pairs, Hypothesis h, const ScoringSet& origins,
                         const RansacOptions& options, double threshold, int max_passes,
                         std::vector<std::uint8_t>& mask) {
  Refined r;
  PairMoments moments;
  for (r.passes = 1;; ++r.passes) {
    // The first pass sums every inlier; later ones only the pairs that joined or left.
    r.last = classify_inliers(pairs, h.T, threshold, origins.origin_in_plan, origins.origin_in_grid,
                              r.passes == 1 ? InlierPassMode::full : InlierPassMode::delta, mask,
                              options.threads);
    if (r.last.first_bad >= 0)
      validate_pair(pairs, r.last.first_bad);
    if (r.passes == 1) {
      moments = r.last.moments;
    } else {
      moments += r.last.moments;
    }
    r.inlier_weight = moments.weight;
    if (r.passes > 1 && r.last.changed == 0) {
      r.stable = true;  // T is the least-squares fit of its own inliers
      break;
    }
    if (r.passes >= max_passes)
      break;
    const TransformEstimationOptions fit = fit_options(options.kind, h.mirrored);
    const std::optional<TransformEstimate> e = fit_transform(moments, fit);
    if (!e) {
      r.note = "the refit stopped: " + degeneracy_reason(moments, fit);
      break;
    }
    h.T = e->T_grid_plan.topRows<2>();
  }
  r.hypothesis = h;
  return r;
}

// ---- adaptive threshold: the noise scale of the winner's residuals ----

int transform_parameters(TransformKind kind) {
  switch (kind) {
    case TransformKind::rigid:
      return 3;
    case TransformKind::affine:
      return 6;
    case TransformKind::similarity:
      break;
  }
  return 4;
}

// |T p - q| of every pair.
std::vector<double> residual_distances(const ReferencePairs& pairs, const Affine& T) {
  const Eigen::Matrix2Xd mapped =
      (T.leftCols<2>() * pairs.points_in_plan).colwise() + T.col(2) - pairs.points_in_grid;
  const Eigen::VectorXd d = mapped.colwise().norm().transpose();
  return {d.data(), d.data() + d.size()};
}

struct Scale {
  Hypothesis hypothesis;    // refitted on its inliers at `threshold`
  double threshold = 0.0;   // metres
  double sigma = 0.0;       // metres per axis (0 when never identified)
  bool identified = false;  // in the last round
  int passes = 0;
};

// Rounds of: refit on the inliers of the threshold, sigma from their residuals, threshold =
// threshold_sigmas sigma (doubled while sigma is not identifiable), until it settles.
Scale adapt_threshold(const ReferencePairs& on, Hypothesis h, const ScoringSet& origins,
                      const RansacOptions& options, double threshold,
                      std::vector<std::uint8_t>& scratch) {
  const double floor = kMinThresholdFraction * std::max(origins.grid_extent, origins.extent);
  const int parameters = transform_parameters(options.kind);
  Scale s;
  s.threshold = threshold;
  for (s.passes = 1; s.passes <= kMaxScalePasses; ++s.passes) {
    h = refit_on_inliers(on, h, origins, options, s.threshold, kSubsetRefitPasses, scratch)
            .hypothesis;
    std::vector<double> distances = residual_distances(on, h.T);
    const std::optional<double> sigma =
        truncated_rayleigh_scale(distances, s.threshold, parameters);
    double next = 2.0 * s.threshold;
    s.identified = sigma.has_value();
    if (sigma) {
      s.sigma = *sigma;
      next = std::max(options.threshold_sigmas * *sigma, floor);
    }
    const bool settled = sigma && std::abs(next - s.threshold) <= kScaleTolerance * s.threshold;
    s.threshold = next;
    if (settled)
      break;
  }
  s.passes = std::min(s.passes, kMaxScalePasses);
  s.hypothesis = h;
  return s;
}

}  // namespace

int required_iterations(double inlier_ratio, int sample_size, double confidence, int min_iterations,
                        int max_iterations) {
  const double all_inliers = std::pow(std::clamp(inlier_ratio, 0.0, 1.0), sample_size);
  double n = static_cast<double>(max_iterations);
  if (all_inliers >= 1.0) {
    n = 0.0;
  } else if (all_inliers > 0.0) {
    n = std::ceil(std::log(1.0 - confidence) / std::log1p(-all_inliers));
  }
  n = std::clamp(n, static_cast<double>(min_iterations), static_cast<double>(max_iterations));
  return static_cast<int>(n);
}

std::vector<Eigen::Index> inlier_indices(const RansacResult& result) {
  std::vector<Eigen::Index> indices;
  indices.reserve(result.inlier_count);
  for (std::size_t i = 0; i < result.inlier_mask.size(); ++i) {
    if (result.inlier_mask[i] != 0)
      indices.push_back(static_cast<Eigen::Index>(i));
  }
  return indices;
}

RansacResult ransac_transform(const ReferencePairs& pairs, const RansacOptions& options) {
  validate_options(options);
  const Eigen::Index n = pairs.size();
  const int sample_size = minimal_sample_size(options.kind);
  if (pairs.points_in_grid.cols() != n || (pairs.has_weights() && pairs.weights.size() != n)) {
    std::ostringstream message;
    message << "mismatched sizes: " << n << " plan points, " << pairs.points_in_grid.cols()
            << " grid points, " << pairs.weights.size() << " weights";
    throw_pairs_error(message.str());
  }
  if (n < sample_size) {
    std::ostringstream message;
    message << "a " << transform_kind_name(options.kind) << " needs at least " << sample_size
            << " pairs (got " << n << ")";
    throw_pairs_error(message.str());
  }
  Random random(options.seed);
  Random subset_random(random.fork());
  Random sample_random(random.fork());

  // Every hypothesis is scored on one fixed subset (all pairs when there are few).
  const ScoringSet scoring =
      make_scoring_set(pairs, draw_subset(n, options.preemptive_subset, subset_random));
  const double separation = options.min_sample_separation * scoring.extent;
  const auto scoring_size = static_cast<double>(scoring.px.size());
  const bool adaptive = !options.inlier_threshold.has_value();
  // Adaptive: the search's threshold, wide, until the noise is measured.
  double threshold = adaptive ? options.search_threshold_fraction * scoring.grid_extent
                              : *options.inlier_threshold;
  if (!(threshold > 0.0))  // all grid points (nearly) equal: any positive scale will do
    threshold = options.search_threshold_fraction * std::max(scoring.extent, 1.0);
  const double threshold2 = threshold * threshold;

  RansacResult result;
  result.threshold_adaptive = adaptive;
  std::vector<Hypothesis> best;
  std::size_t best_inliers = 0;
  int needed = options.max_iterations;
  Eigen::Index sample[3];
  for (; result.iterations < needed; ++result.iterations) {
    for (int k = 0; k < sample_size; ++k) {
      bool repeated = false;
      do {
        sample[k] = sample_random.integer(0, n - 1);
        repeated = std::find(sample, sample + k, sample[k]) != sample + k;
      } while (repeated);
    }
    std::vector<Hypothesis> candidates = hypotheses_from_sample(pairs, sample, options, separation);
    if (candidates.empty())
      ++result.degenerate_samples;
    for (Hypothesis& h : candidates) {
      h.score = score_hypothesis(scoring, h.T, threshold2);
      keep_best(best, h, static_cast<std::size_t>(options.verify_count));
      if (h.score.inliers > best_inliers) {
        best_inliers = h.score.inliers;
        needed =
            required_iterations(static_cast<double>(best_inliers) / scoring_size, sample_size,
                                options.confidence, options.min_iterations, options.max_iterations);
      }
    }
  }
  if (best.empty()) {
    // No usable minimal sample: start from the least-squares fit of all pairs (which throws
    // when the pairs themselves are degenerate).
    const TransformEstimate all =
        estimate_transform(pairs.points_in_plan, pairs.points_in_grid, pairs.weights,
                           {options.kind, options.reflection});
    best.push_back({all.T_grid_plan.topRows<2>(), all.reflected, {}});
    result.message = "no minimal sample was usable; started from the fit of all pairs";
  }

  // The best few are re-scored on a larger subset, and the winner refitted there first, so
  // that the passes over all pairs start close to their fixed point.
  Hypothesis winner = best.front();
  std::vector<std::uint8_t> scratch;
  const bool verify_on_all = static_cast<std::size_t>(n) <= options.verify_subset;
  ReferencePairs verify;
  const bool scored_on_all =
      static_cast<std::size_t>(scoring.px.size()) == static_cast<std::size_t>(n);
  if (!verify_on_all && (!scored_on_all || adaptive))
    verify = gather_pairs(pairs, draw_subset(n, options.verify_subset, subset_random));
  const ReferencePairs& on = verify_on_all ? pairs : verify;
  if (!scored_on_all) {
    if (best.size() > 1) {
      double best_cost = INFINITY;
      for (const Hypothesis& h : best) {
        const double cost = msac_cost(on, h.T, threshold, options.threads);
        if (cost < best_cost)
          best_cost = cost, winner = h;
      }
    }
    if (!verify_on_all && !adaptive) {
      winner =
          refit_on_inliers(verify, winner, scoring, options, threshold, kSubsetRefitPasses, scratch)
              .hypothesis;
    }
  }
  if (adaptive) {
    // The noise is measured on the verification subset (all pairs when few): tens of
    // thousands of residuals pin sigma down as well as millions.
    const Scale scale = adapt_threshold(on, winner, scoring, options, threshold, scratch);
    winner = scale.hypothesis;
    threshold = scale.threshold;
    result.noise_sigma = scale.sigma;
    result.scale_passes = scale.passes;
    if (!scale.identified) {
      std::ostringstream text;
      text << (result.message.empty() ? "" : "; ")
           << "the noise of the residuals did not settle to a measurable scale; the threshold "
              "was widened to "
           << threshold << " m";
      result.message += text.str();
    }
  }
  result.inlier_threshold = threshold;

  const Refined refined = refit_on_inliers(pairs, winner, scoring, options, threshold,
                                           options.max_refit_passes, result.inlier_mask);
  result.refit_passes = refined.passes;
  result.inlier_count = refined.last.inliers;
  result.estimate.T_grid_plan.topRows<2>() = refined.hypothesis.T;
  const Eigen::Matrix2d linear = refined.hypothesis.T.leftCols<2>();
  result.estimate.reflected = linear.determinant() < 0.0;
  result.estimate.scale =
      options.kind == TransformKind::rigid ? 1.0 : std::sqrt(std::abs(linear.determinant()));
  result.estimate.rms =
      refined.inlier_weight > 0.0 ? std::sqrt(refined.last.squared / refined.inlier_weight) : 0.0;

  std::ostringstream note;
  if (!result.message.empty())
    note << result.message;
  const auto add_note = [&](const std::string& text) {
    if (note.tellp() > 0)
      note << "; ";
    note << text;
  };
  if (!refined.note.empty())
    add_note(refined.note);
  if (!refined.stable && refined.note.empty()) {
    add_note("inliers still changed in the last of " + std::to_string(refined.passes) +
             " refit passes");
  }
  result.ok =
      result.inlier_count >= static_cast<std::size_t>(sample_size) && refined.inlier_weight > 0.0;
  if (!result.ok) {
    add_note("only " + std::to_string(result.inlier_count) +
             " pairs lie within inlier_threshold of the best hypothesis");
  }
  result.message = note.str();
  return result;
}

}  // namespace floorgrid
