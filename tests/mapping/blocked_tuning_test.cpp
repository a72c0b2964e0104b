// What the non-rigid models do away from their pairs, against known truth: gp reverts to a
// similarity far from the pairs (not to the pairs' centroid), and the smoothing of tps and the
// scale of the GP's kernel, chosen on spatially blocked folds, beat interpolating pairs whose
// noise is shared by near-copies (as a laser scan's pairs share a localization error).
#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "tests/mapping/mapping_test_data.hpp"

namespace floorgrid {
namespace {

/// Mean |model - truth| over a 1 m lattice of the test domain.
double truth_error(const PointMapping& model, const test::Truth& truth) {
  double sum = 0.0;
  int count = 0;
  for (double x = 0.5; x < test::kWidth; x += 1.0) {
    for (double y = 0.5; y < test::kHeight; y += 1.0) {
      sum += (model.forward({x, y}) - truth({x, y})).norm();
      ++count;
    }
  }
  return sum / count;
}

/// Pairs in clusters of `copies` near-copies (within 3 cm) that share one normal offset of
/// `sigma` metres per axis: the noise a localization error puts on every pair of a scan.
ReferencePairs clustered_pairs(int clusters, int copies, const test::Truth& truth, double sigma,
                               std::uint64_t seed) {
  Random r(seed);
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, clusters * copies);
  pairs.points_in_grid.resize(2, clusters * copies);
  for (int c = 0; c < clusters; ++c) {
    const Eigen::Vector2d centre(r.uniform(0.0, test::kWidth), r.uniform(0.0, test::kHeight));
    const Eigen::Vector2d offset(r.normal(sigma), r.normal(sigma));
    for (int k = 0; k < copies; ++k) {
      const Eigen::Vector2d p =
          centre + Eigen::Vector2d(r.uniform(-0.03, 0.03), r.uniform(-0.03, 0.03));
      pairs.points_in_plan.col(c * copies + k) = p;
      pairs.points_in_grid.col(c * copies + k) = truth(p) + offset;
    }
  }
  return pairs;
}

MappingOptions model_options(const std::string& name) {
  MappingOptions options;
  options.model = name;
  return options;
}

TEST(GpExtrapolation, FarFromThePairsGpRevertsToTheSimilarityNotToTheirCentroid) {
  // Pairs only in a 10 x 10 m corner of a similarity with 2 cm noise; 30-60 m away, a
  // constant mean would put every point near the corner's centroid, tens of metres off.
  const test::Truth truth = test::similarity(0.4, 1.3, {7.0, -2.0});
  Random r(3);
  Eigen::Matrix2Xd plan(2, 300);
  for (Eigen::Index i = 0; i < plan.cols(); ++i)
    plan.col(i) << r.uniform(0.0, 10.0), r.uniform(0.0, 10.0);
  const ReferencePairs pairs = test::make_pairs(plan, truth, 0.02, 4);
  for (const char* name : {"gp", "gpgt"}) {
    auto model = make_mapping(model_options(name));
    model->fit(pairs);
    for (const Eigen::Vector2d& far :
         {Eigen::Vector2d(40.0, 5.0), Eigen::Vector2d(-30.0, 30.0), Eigen::Vector2d(50.0, 50.0)}) {
      // The similarity fitted on a 10 m patch with 2 cm noise: its rotation and scale are
      // good to about 0.3 mrad, so 60 m away a few cm.
      EXPECT_LT((model->forward(far) - truth(far)).norm(), 0.1)
          << name << " at " << far.transpose();
    }
  }
}

TEST(BlockedTuning, TpsSmoothingChosenOnBlocksBeatsInterpolatingSharedNoise) {
  const test::Truth truth = test::bent();
  const ReferencePairs pairs = clustered_pairs(150, 10, truth, 0.08, 11);
  auto chosen = make_mapping(model_options("tps"));
  chosen->fit(pairs);
  MappingOptions interpolating = model_options("tps");
  interpolating.tps.regularization = 0.0;
  auto interpolation = make_mapping(interpolating);
  interpolation->fit(pairs);
  const double chosen_error = truth_error(*chosen, truth);
  const double interpolation_error = truth_error(*interpolation, truth);
  // Shared offsets of 8 cm per axis: the interpolation reproduces them (about 0.1 m mean),
  // a smoothing that averages several clusters does not.
  EXPECT_LT(chosen_error, 0.7 * interpolation_error)
      << "chosen " << chosen_error << " m, interpolating " << interpolation_error << " m";
}

TEST(BlockedTuning, GpKernelScaleChosenOnBlocksBeatsTheLikelihoodsOnSharedNoise) {
  const test::Truth truth = test::bent();
  const ReferencePairs pairs = clustered_pairs(150, 10, truth, 0.08, 12);
  // gpgt: gp's kernel is at least a quarter of the pairs' extent long, which the likelihood
  // already reaches here.
  for (const char* name : {"gpgt"}) {
    auto chosen = make_mapping(model_options(name));
    const FitSummary summary = chosen->fit(pairs);
    const Value* likelihood = summary.details.find("likelihood_hyperparameters");
    ASSERT_NE(likelihood, nullptr);
    ASSERT_TRUE(likelihood->is_object());
    GpHyperparameters h;
    h.length_scale << likelihood->find("length_scale_m")->items()[0].as_number(),
        likelihood->find("length_scale_m")->items()[1].as_number();
    h.signal_std = likelihood->find("signal_std_m")->as_number();
    h.noise_std = likelihood->find("noise_std_m")->as_number();
    MappingOptions given = model_options(name);
    given.gp.hyperparameters = h;
    auto by_likelihood = make_mapping(given);
    by_likelihood->fit(pairs);
    const double chosen_error = truth_error(*chosen, truth);
    const double likelihood_error = truth_error(*by_likelihood, truth);
    EXPECT_LT(chosen_error, 0.8 * likelihood_error)
        << name << ": blocked " << chosen_error << " m, likelihood " << likelihood_error << " m";
  }
}

}  // namespace
}  // namespace floorgrid
