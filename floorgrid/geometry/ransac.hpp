#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

/// Options of ransac_transform. Defaults suit pairs in metres of any noise: laser pairs
/// (centimetres) and hand-picked ones (decimetres).
struct RansacOptions {
  TransformKind kind = TransformKind::similarity;  ///< the family fitted
  /// Similarity and rigid: `allow` scores a proper and a mirrored hypothesis per sample.
  Reflection reflection = Reflection::allow;
  /// metres: a pair is an inlier when |T p - q| <= this. Unset: adaptive, `threshold_sigmas`
  /// times the noise scale of the pairs, estimated from the residuals of the fit.
  std::optional<double> inlier_threshold;
  /// Adaptive threshold: its multiple of the noise scale sigma (metres per axis). 3 keeps
  /// 98.9% of Gaussian inliers (|T p - q| is Rayleigh(sigma): exp(-3^2 / 2) = 1.1% lie beyond).
  double threshold_sigmas = 3.0;
  /// Adaptive threshold: the threshold of the search for hypotheses, before the noise is known,
  /// as a share of the grid points' extent (the diagonal of their 5th-95th percentile box).
  double search_threshold_fraction = 0.02;
  double confidence = 0.999;   ///< in (0, 1): wanted probability of one all-inlier sample
  int max_iterations = 10000;  ///< minimal samples drawn at most
  int min_iterations = 20;     ///< minimal samples drawn at least
  std::uint64_t seed = 1;      ///< same seed, same result
  /// Pairs (a fixed random subset) on which every hypothesis is scored; all pairs when fewer.
  std::size_t preemptive_subset = 2000;
  int verify_count = 4;  ///< best hypotheses on that subset re-scored on the verification subset
  /// Pairs (a fixed random subset) on which the best few are re-scored and refitted until their
  /// inliers are stable, before the passes over all pairs; all pairs when fewer.
  std::size_t verify_subset = 50000;
  int max_refit_passes = 3;  ///< passes over all pairs (classify, then refit) at most; >= 1
  /// Samples whose plan points lie closer than this fraction of the pairs' extent (bounding
  /// box diagonal), or (affine) whose triangle is flatter than that, are rejected.
  double min_sample_separation = 0.02;
  /// Threads of the passes over all pairs: 1 or 2 (the second only from 2^18 pairs on); the
  /// result does not depend on it.
  int threads = kDefaultThreads;
};

/// The outcome of ransac_transform.
struct RansacResult {
  bool ok = false;      ///< false when too few pairs agree with any hypothesis (see message)
  std::string message;  ///< why not ok, or a note (empty when there is nothing to say)
  /// The transform refitted on its inliers; `rms` is over the inliers, in metres.
  TransformEstimate estimate;
  /// One entry per pair: 1 when |T p - q| <= inlier_threshold under the returned transform.
  std::vector<std::uint8_t> inlier_mask;
  /// metres: the threshold the inliers were classified with (the given one, or the adaptive
  /// one; 0 when the fit did not get that far).
  double inlier_threshold = 0.0;
  bool threshold_adaptive = false;  ///< whether inlier_threshold was adapted to the noise
  /// Adaptive threshold: the pairs' noise scale sigma, metres per axis (0 when given).
  double noise_sigma = 0.0;
  /// Adaptive threshold: rounds of refit and re-estimated sigma (0 when given).
  int scale_passes = 0;
  std::size_t inlier_count = 0;  ///< pairs with inlier_mask 1
  int iterations = 0;            ///< minimal samples drawn (degenerate ones included)
  int degenerate_samples = 0;    ///< samples rejected as too close or collinear
  int refit_passes = 0;          ///< passes over all pairs
};

/// Robust plan-to-grid transform (thesis 3.2.2, 4.2): RANSAC over minimal samples (2 pairs for
/// similarity and rigid, 3 for affine), then a weighted least-squares refit on the inliers.
///
/// Scoring (MSAC): a hypothesis costs sum_i w_i min(|T p_i - q_i|^2, threshold^2), lower is
/// better, on a fixed random subset of `preemptive_subset` pairs; the adaptive sample count
/// N = log(1 - confidence) / log(1 - r^s) uses the best inlier ratio r seen on that subset.
/// The `verify_count` best are re-scored on `verify_subset` pairs, and the winner is refitted
/// there until its inlier set is stable. Refit: classify every pair under T, refit T on the
/// inliers (weighted least squares, the winner's handedness kept), repeat until the inlier set
/// is unchanged or `max_refit_passes` passes over all pairs are done; the reported inliers and
/// rms are those of the returned T. Deterministic for a seed, whatever `threads`.
///
/// Adaptive threshold (`inlier_threshold` unset; MSAC with an estimated scale, as in
/// MLESAC/MAGSAC): the search scores hypotheses at `search_threshold_fraction` of the grid
/// points' extent (wide, so that noise of any size is inside; outliers spread over the map
/// rarely are). Then, on the verification subset (all pairs when few), rounds of: refit the
/// winner on its inliers, estimate sigma from their residuals (truncated_rayleigh_scale, the
/// median corrected for the cut), set the threshold to `threshold_sigmas` sigma (doubled
/// instead while sigma is not identifiable), until the threshold changes by less than 1%. The
/// threshold never falls below 1e-6 of the extent (exact pairs). The passes over all pairs use
/// the final threshold. With a given threshold the result is what it always was.
///
/// Throws InputError naming `pairs` on mismatched sizes, fewer pairs than a minimal sample,
/// NaN or infinite coordinates, negative or NaN weights, or degenerate pairs (all plan points
/// equal; collinear for affine), and naming `ransac.<field>` on bad options.
RansacResult ransac_transform(const ReferencePairs& pairs, const RansacOptions& options = {});

/// The indices of the pairs marked in `result.inlier_mask`, ascending.
std::vector<Eigen::Index> inlier_indices(const RansacResult& result);

/// The adaptive RANSAC sample count: log(1 - confidence) / log(1 - inlier_ratio^sample_size),
/// rounded up and clamped to [min_iterations, max_iterations].
int required_iterations(double inlier_ratio, int sample_size, double confidence, int min_iterations,
                        int max_iterations);

}  // namespace floorgrid
