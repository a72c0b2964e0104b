// RANSAC for the global transforms: 10^5 pairs with 60% outliers and 10^7 pairs with 30%
// outliers (targets: 5 ms and 150 ms), and, when OpenCV's calib3d is installed, side by side
// with cv::estimateAffinePartial2D on 10^5 pairs with 30% outliers.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/ransac.hpp"

#ifdef FLOORGRID_HAVE_OPENCV_CALIB3D
#include <opencv2/calib3d.hpp>
#endif

namespace {

using floorgrid::RansacOptions;
using floorgrid::RansacResult;
using floorgrid::ReferencePairs;

constexpr double kWidth = 100.0;  // metres: the plan points lie in [0, 100] x [0, 60]
constexpr double kHeight = 60.0;
constexpr double kNoise = 0.01;  // metres per axis on the inliers

// The true plan-to-grid similarity.
Eigen::Matrix3d truth() {
  const double angle = 0.7, scale = 1.02;
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T.topLeftCorner<2, 2>() << scale * std::cos(angle), -scale * std::sin(angle),
      scale * std::sin(angle), scale * std::cos(angle);
  T.topRightCorner<2, 1>() = Eigen::Vector2d(25.0, -13.0);
  return T;
}

// Pairs with `outlier_percent` % outliers (grid point uniform over the grown image of the box),
// built once per size.
const ReferencePairs& pairs(long count, long outlier_percent) {
  static std::map<std::pair<long, long>, std::unique_ptr<ReferencePairs>> cache;
  std::unique_ptr<ReferencePairs>& slot = cache[{count, outlier_percent}];
  if (slot)
    return *slot;
  slot = std::make_unique<ReferencePairs>();
  floorgrid::Random random(static_cast<std::uint64_t>(count + outlier_percent));
  const Eigen::Matrix3d T = truth();
  slot->points_in_plan.resize(2, count);
  slot->points_in_grid.resize(2, count);
  for (long i = 0; i < count; ++i) {
    const Eigen::Vector2d p(random.uniform(0, kWidth), random.uniform(0, kHeight));
    slot->points_in_plan.col(i) = p;
    Eigen::Vector2d q;
    if (random.uniform() * 100.0 < static_cast<double>(outlier_percent)) {
      q = Eigen::Vector2d(random.uniform(-20, kWidth + 20), random.uniform(-20, kHeight + 20));
    } else {
      q = p + Eigen::Vector2d(random.normal(kNoise), random.normal(kNoise)) / 1.02;
    }
    slot->points_in_grid.col(i) = T.topLeftCorner<2, 2>() * q + T.topRightCorner<2, 1>();
  }
  return *slot;
}

// Largest distance between a transform's and the truth's images over the plan box.
double error_m(const Eigen::Matrix<double, 2, 3>& T) {
  const Eigen::Matrix3d truth_T = truth();
  double worst = 0.0;
  for (const Eigen::Vector3d& corner :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(kWidth, 0, 1), Eigen::Vector3d(0, kHeight, 1),
        Eigen::Vector3d(kWidth, kHeight, 1)}) {
    worst = std::max(worst, (T * corner - truth_T.topRows<2>() * corner).norm());
  }
  return worst;
}

void report(benchmark::State& state, const RansacResult& r) {
  state.counters["error_m"] = error_m(r.estimate.T_grid_plan.topRows<2>());
  state.counters["iterations"] = r.iterations;
  state.counters["refit_passes"] = r.refit_passes;
  state.counters["inliers"] = static_cast<double>(r.inlier_count);
  state.counters["rms_m"] = r.estimate.rms;
}

// Args: pairs, outlier percent, threads.
void BM_RansacSimilarity(benchmark::State& state) {
  const ReferencePairs& data = pairs(state.range(0), state.range(1));
  RansacOptions options;
  options.threads = static_cast<int>(state.range(2));
  RansacResult result;
  for (auto _ : state) {
    result = floorgrid::ransac_transform(data, options);
    benchmark::DoNotOptimize(result.estimate.T_grid_plan.data());
  }
  report(state, result);
}
BENCHMARK(BM_RansacSimilarity)
    ->Args({100000, 60, 1})
    ->Args({100000, 60, 2})
    ->Args({100000, 30, 2})
    ->Args({10000000, 30, 1})
    ->Args({10000000, 30, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Args: pairs, outlier percent.
void BM_RansacAffine(benchmark::State& state) {
  const ReferencePairs& data = pairs(state.range(0), state.range(1));
  RansacOptions options;
  options.kind = floorgrid::TransformKind::affine;
  RansacResult result;
  for (auto _ : state) {
    result = floorgrid::ransac_transform(data, options);
    benchmark::DoNotOptimize(result.estimate.T_grid_plan.data());
  }
  report(state, result);
}
BENCHMARK(BM_RansacAffine)->Args({100000, 60})->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef FLOORGRID_HAVE_OPENCV_CALIB3D
// OpenCV's 4-degree-of-freedom RANSAC (same threshold and confidence, its default
// Levenberg-Marquardt refinement) on float points prepared outside the timing. Counters: its
// error, and floorgrid's time (median of 7 runs, 2 threads) and error on the same pairs, and
// the speed ratio opencv_ms / floorgrid_ms.
void BM_OpenCvEstimateAffinePartial2D(benchmark::State& state) {
  const ReferencePairs& data = pairs(state.range(0), state.range(1));
  std::vector<cv::Point2f> from(static_cast<std::size_t>(data.size()));
  std::vector<cv::Point2f> to(from.size());
  for (Eigen::Index i = 0; i < data.size(); ++i) {
    from[static_cast<std::size_t>(i)] = cv::Point2f(static_cast<float>(data.points_in_plan(0, i)),
                                                    static_cast<float>(data.points_in_plan(1, i)));
    to[static_cast<std::size_t>(i)] = cv::Point2f(static_cast<float>(data.points_in_grid(0, i)),
                                                  static_cast<float>(data.points_in_grid(1, i)));
  }
  RansacOptions options;
  options.inlier_threshold = 0.10;  // OpenCV needs one: the same for both
  cv::Mat T;
  std::vector<std::uint8_t> inliers;
  std::vector<double> seconds;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    T = cv::estimateAffinePartial2D(from, to, inliers, cv::RANSAC, *options.inlier_threshold,
                                    static_cast<std::size_t>(options.max_iterations),
                                    options.confidence);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(T.data);
  }
  Eigen::Matrix<double, 2, 3> cv_T;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c)
      cv_T(r, c) = T.at<double>(r, c);
  }
  std::vector<double> ours;
  RansacResult result;
  for (int run = 0; run < 7; ++run) {
    const auto start = std::chrono::steady_clock::now();
    result = floorgrid::ransac_transform(data, options);
    ours.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ours.begin(), ours.end());
  std::sort(seconds.begin(), seconds.end());
  const double opencv_median = seconds[seconds.size() / 2];
  state.counters["opencv_error_m"] = error_m(cv_T);
  state.counters["opencv_inliers"] =
      static_cast<double>(std::count(inliers.begin(), inliers.end(), std::uint8_t{1}));
  state.counters["floorgrid_ms"] = 1e3 * ours[3];
  state.counters["floorgrid_error_m"] = error_m(result.estimate.T_grid_plan.topRows<2>());
  state.counters["opencv_over_floorgrid"] = opencv_median / ours[3];
}
BENCHMARK(BM_OpenCvEstimateAffinePartial2D)
    ->Args({100000, 30})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
