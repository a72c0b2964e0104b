// compare_models with error pairs: models fitted on one set of pairs (align's slid
// pairs) state the cross-validated error and std_m of another (the filters' own).
#include "floorgrid/evaluation/model_comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid {
namespace {

Eigen::Vector2d bend(const Eigen::Vector2d& p) {
  return {1.02 * p.x() + 3.0, p.y() - 1.0 + 0.3 * std::sin(p.x() / 6.0)};
}

/// Pairs along a tour of a 30 x 20 m floor, in tour order: exactly on the truth, and the same
/// with every 40 pairs (a scan) sharing one pose error of 8 cm.
std::pair<ReferencePairs, ReferencePairs> tour_pairs() {
  Random random(11);
  const int n = 1600;
  ReferencePairs exact, noisy;
  exact.points_in_plan.resize(2, n);
  exact.points_in_grid.resize(2, n);
  Eigen::Vector2d scan_error = Eigen::Vector2d::Zero();
  for (int i = 0; i < n; ++i) {
    const double s = 0.06 * i;  // a lawn-mower tour, 2 m between its lanes
    const int lane = static_cast<int>(s / 30.0);
    const double along = std::fmod(s, 30.0);
    const Eigen::Vector2d p(lane % 2 == 0 ? along : 30.0 - along, 2.0 * lane + random.normal(0.3));
    exact.points_in_plan.col(i) = p;
    exact.points_in_grid.col(i) = bend(p);
  }
  noisy = exact;
  for (int i = 0; i < n; ++i) {
    if (i % 40 == 0)
      scan_error = Eigen::Vector2d(random.normal(0.08), random.normal(0.08));
    noisy.points_in_grid.col(i) += scan_error;
  }
  return {exact, noisy};
}

TEST(ModelComparison, CvAndStdComeFromTheErrorSourceWhileTheFitUsesThePairs) {
  const auto [exact, noisy] = tour_pairs();
  ModelComparisonOptions options;
  options.models = {"tps"};
  const EvaluationDomain no_domain{"none", Eigen::Matrix2Xd(2, 0), 0.05, std::nullopt};
  const std::optional<PairNoise> noise = pair_noise(noisy);
  ASSERT_TRUE(noise);

  const std::vector<ModelReport> own =
      compare_models(exact, no_domain, std::nullopt, pair_noise(exact), options);
  const std::vector<ModelReport> other =
      compare_models(exact, no_domain, std::nullopt, noise, options, {}, &noisy);
  ASSERT_TRUE(own[0].model && other[0].model);

  // Fitted on the exact pairs either way: the same map.
  for (const Eigen::Index i : {0, 400, 1200})
    EXPECT_NEAR((other[0].model->forward(exact.points_in_plan.col(i)) -
                 own[0].model->forward(exact.points_in_plan.col(i)))
                    .norm(),
                0.0, 1e-12);
  // The held-out error is the noisy pairs' blocked cross-validation, exactly.
  MappingOptions tps = options.mapping;
  tps.model = "tps";
  CrossValidationOptions blocked = options.mapping.auto_select.cv;
  blocked.folds = options.cv_folds;
  blocked.kind = CrossValidationKind::blocked;
  ASSERT_TRUE(other[0].summary.cv_error_m && own[0].summary.cv_error_m);
  EXPECT_DOUBLE_EQ(*other[0].summary.cv_error_m, cross_validate(tps, noisy, blocked).mean_error_m);
  EXPECT_GT(*other[0].summary.cv_error_m, 3.0 * *own[0].summary.cv_error_m);
  // And so is std_m: wider than the exact pairs', which hold no noise.
  const Eigen::Vector2d middle(15.0, 10.0);
  ASSERT_TRUE(other[0].model->error_std(middle) && own[0].model->error_std(middle));
  EXPECT_GT(*other[0].model->error_std(middle), 2.0 * *own[0].model->error_std(middle));
}

}  // namespace
}  // namespace floorgrid
