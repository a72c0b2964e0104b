#include "floorgrid/mapping/gp_blocked_tuning.hpp"

#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/cross_validation_folds.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"

namespace floorgrid {

namespace {

/// Mean held-out error of a GP with hyperparameters `h` over `folds`.
double held_out_error(Eigen::Ref<const Eigen::Matrix2Xd> points,
                      Eigen::Ref<const Eigen::Matrix2Xd> outputs, const Folds& folds,
                      const GpHyperparameters& h) {
  GaussianProcessOptions options;
  options.hyperparameters = h;
  options.prediction.lattice.enabled = false;  // a few predictions each: the exact mean
  options.prediction.threads = 1;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t f = 0; f < folds.count; ++f) {
    std::vector<Eigen::Index> train, test;
    folds.split(f, train, test);
    if (train.size() < 3 || test.empty())
      continue;
    Eigen::Matrix2Xd train_points(2, static_cast<Eigen::Index>(train.size()));
    Eigen::Matrix2Xd train_outputs(2, train_points.cols());
    for (std::size_t k = 0; k < train.size(); ++k) {
      train_points.col(static_cast<Eigen::Index>(k)) = points.col(train[k]);
      train_outputs.col(static_cast<Eigen::Index>(k)) = outputs.col(train[k]);
    }
    try {
      const GaussianProcessFit fit = fit_gaussian_process(train_points, train_outputs, options);
      for (const Eigen::Index i : test) {
        sum += (fit.model.exact_mean(points.col(i)) - outputs.col(i)).norm();
        ++count;
      }
    } catch (const InputError&) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : std::numeric_limits<double>::infinity();
}

}  // namespace

GpBlockedTuning refine_by_blocked_cv(Eigen::Ref<const Eigen::Matrix2Xd> points,
                                     Eigen::Ref<const Eigen::Matrix2Xd> outputs,
                                     const Eigen::Matrix2Xd& blocks_at,
                                     const GpHyperparameters& tuned, std::size_t folds,
                                     std::uint64_t seed) {
  GpBlockedTuning result;
  result.hyperparameters = tuned;
  const Folds dealt = blocked_folds(blocks_at, folds, choose_block_size(blocks_at, folds), seed);
  result.block_size = dealt.block_size;
  result.folds = dealt.count;
  if (dealt.count < 2)
    return result;  // one block: nothing to hold out
  double best = std::numeric_limits<double>::infinity();
  for (const double length : kGpLengthFactors) {
    for (const double noise : kGpNoiseFactors) {
      GpHyperparameters h = tuned;
      h.length_scale *= length;
      h.noise_std *= noise;
      const double error = held_out_error(points, outputs, dealt, h);
      result.table.push_back({length, noise, error});
      if (error < best) {
        best = error;
        result.hyperparameters = h;
      }
    }
  }
  return result;
}

}  // namespace floorgrid
