// One contract over every mapping model (STYLE habit 9): a new model is one line in kModels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/convex_hull.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_file.hpp"
#include "tests/mapping/mapping_test_data.hpp"

namespace floorgrid {
namespace {

using test::domain_extent;
using test::make_pairs;
using test::random_points;
using test::Truth;

/// One model of the registry under test: its name and what it promises beyond the common
/// contract (ModelTraits). Adding a model to the registry adds it to every suite here.
struct Model {
  std::string name;
  ModelTraits traits;
};

void PrintTo(const Model& model, std::ostream* os) {
  *os << model.name;
}

/// Every model of the registry.
std::vector<Model> all_models() {
  std::vector<Model> out;
  for (const ModelEntry& entry : model_registry())
    out.push_back({std::string(entry.name), entry.traits});
  return out;
}

/// The models with a given promise.
std::vector<Model> models_where(bool ModelTraits::*promise) {
  std::vector<Model> out;
  for (const Model& m : all_models()) {
    if (m.traits.*promise)
      out.push_back(m);
  }
  return out;
}

std::unique_ptr<PointMapping> fitted(const std::string& name, const ReferencePairs& pairs) {
  MappingOptions options;
  options.model = name;
  auto mapping = make_mapping(options);
  mapping->fit(pairs);
  return mapping;
}

/// Random points inside the convex hull of the pairs' plan points.
Eigen::Matrix2Xd points_in_hull(const ReferencePairs& pairs, int n, std::uint64_t seed) {
  const auto hull = convex_hull(pairs.points_in_plan);
  Random r(seed);
  Eigen::Matrix2Xd out(2, n);
  const Eigen::Vector2d lo = pairs.points_in_plan.rowwise().minCoeff();
  const Eigen::Vector2d hi = pairs.points_in_plan.rowwise().maxCoeff();
  for (int i = 0; i < n;) {
    const Eigen::Vector2d p(r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y()));
    if (inside_convex_polygon(hull, p, -1e-9))
      out.col(i++) = p;
  }
  return out;
}

double max_error(const PointMapping& m, const Eigen::Matrix2Xd& points, const Truth& truth) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    worst = std::max(worst, (m.forward(points.col(i)) - truth(points.col(i))).norm());
  }
  return worst;
}

double mean_error(const PointMapping& m, const Eigen::Matrix2Xd& points, const Truth& truth,
                  double seam_band = -1.0) {
  double sum = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    if (seam_band > 0.0 && std::abs(points(0, i) - test::kWidth / 2) < seam_band)
      continue;
    sum += (m.forward(points.col(i)) - truth(points.col(i))).norm();
    ++n;
  }
  return sum / n;
}

class MappingContract : public ::testing::TestWithParam<Model> {};

TEST_P(MappingContract, IdentityPairsMapToIdentity) {
  const Truth identity = [](const Eigen::Vector2d& p) { return p; };
  const ReferencePairs pairs = make_pairs(random_points(1000, 1), identity, 0.0, 2);
  const auto m = fitted(GetParam().name, pairs);
  EXPECT_LE(max_error(*m, points_in_hull(pairs, 1000, 3), identity),
            GetParam().traits.identity_tolerance * domain_extent());
}

class ExactModels : public ::testing::TestWithParam<Model> {};

TEST_P(ExactModels, RecoverASimilarityExactly) {
  const Truth truth = test::similarity(2.1, 1.07, {-31.0, 12.5});
  const ReferencePairs pairs = make_pairs(random_points(1000, 4), truth, 0.0, 5);
  const auto m = fitted(GetParam().name, pairs);
  EXPECT_LE(max_error(*m, points_in_hull(pairs, 1000, 6), truth), 1e-10 * domain_extent());
}

class NonRigidModels : public ::testing::TestWithParam<Model> {};

TEST_P(NonRigidModels, BeatAGlobalTransformByHalf) {
  const Eigen::Matrix2Xd plan = random_points(1000, 7);
  const double spacing = std::sqrt(test::kWidth * test::kHeight / 1000.0);
  for (const auto& [label, truth, band] :
       {std::tuple<const char*, Truth, double>{"two regions", test::two_regions(), 2.0 * spacing},
        std::tuple<const char*, Truth, double>{"bent", test::bent(), -1.0}}) {
    const ReferencePairs pairs = make_pairs(plan, truth, 0.01, 8);
    const Eigen::Matrix2Xd probes = points_in_hull(pairs, 2000, 9);
    // The yardstick is the global similarity of one consistent part (RANSAC at a fixed 0.1 m,
    // as when this test was written). gt's default, the threshold adapted to the residuals,
    // spreads its error over both parts and lowers the mean (two regions 0.100 m instead of
    // 0.121 m, bent 0.132 m instead of 0.209 m), and ct, at 0.058 m on two regions, does not
    // halve that.
    MappingOptions one_part;
    one_part.model = "gt";
    one_part.ransac.inlier_threshold = 0.10;
    const auto global = make_mapping(one_part);
    global->fit(pairs);
    const double gt = mean_error(*global, probes, truth, band);
    const double model = mean_error(*fitted(GetParam().name, pairs), probes, truth, band);
    EXPECT_LE(model, 0.5 * gt) << label << ": " << GetParam().name << " " << model << " m vs gt "
                               << gt << " m";
  }
}

TEST_P(MappingContract, RoundTripReturnsToTheStart) {
  const ReferencePairs pairs = make_pairs(random_points(1000, 10), test::bent(), 0.01, 11);
  const auto m = fitted(GetParam().name, pairs);
  const Eigen::Matrix2Xd probes = points_in_hull(pairs, 1000, 12);
  int good = 0;
  for (Eigen::Index i = 0; i < probes.cols(); ++i) {
    const InverseMapping back = m->inverse(m->forward(probes.col(i)));
    if (back.invertible && (back.point - probes.col(i)).norm() <= 1e-6)
      ++good;
  }
  EXPECT_GE(good, GetParam().traits.round_trip_share * 1000) << GetParam().name;
}

TEST_P(MappingContract, RoundTripNeverReturnsAnotherPoint) {
  // Pairs as dense as their noise (laser pairs are): piecewise models fold or jump between
  // neighbours, smooth ones may fold. A point comes back to where it started or is not
  // invertible (SPEC: never garbage), inside the pairs' hull and beyond it.
  const Truth truth = test::bent();
  const ReferencePairs pairs = make_pairs(random_points(3000, 21), truth, 0.15, 22);
  const auto m = fitted(GetParam().name, pairs);
  Random r(23);
  const Eigen::Vector2d lo = pairs.points_in_plan.rowwise().minCoeff().array() - 3.0;
  const Eigen::Vector2d hi = pairs.points_in_plan.rowwise().maxCoeff().array() + 3.0;
  int lost = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y()));
    const InverseMapping back = m->inverse(m->forward(p));
    if (!back.invertible) {
      ++lost;
      continue;
    }
    ASSERT_LE((back.point - p).norm(), 1e-6) << GetParam().name << " took (" << p.transpose()
                                             << ") back to (" << back.point.transpose() << ")";
  }
  // Most points are still invertible.
  EXPECT_LE(lost, 2000 * (1.0 - GetParam().traits.round_trip_share) * 4) << GetParam().name;
}

TEST_P(MappingContract, PoseHeadingTurnsWithTheMapping) {
  const Truth truth = test::similarity(0.4, 1.0, {3.0, -2.0});
  const auto m = fitted(GetParam().name, make_pairs(random_points(1000, 13), truth, 0.0, 14));
  for (const double heading : {0.0, 1.0, -2.5}) {
    const Pose2 g = m->forward_pose({20.0, 10.0, heading});
    EXPECT_NEAR(normalize_angle(g.theta - heading - 0.4), 0.0, 1e-6) << GetParam().name;
    const auto back = m->inverse_pose(g);
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->x, 20.0, 1e-6);
    EXPECT_NEAR(normalize_angle(back->theta - heading), 0.0, 1e-6);
  }
}

TEST_P(MappingContract, SaveThenLoadGivesIdenticalPredictions) {
  const ReferencePairs pairs = make_pairs(random_points(1000, 15), test::bent(), 0.01, 16);
  const auto m = fitted(GetParam().name, pairs);
  const auto loaded =
      load_mapping(io::parse_json(io::dump_json(m->to_model_file()), "model.json"), "model.json");
  EXPECT_EQ(loaded->name(), GetParam().name);
  const Eigen::Matrix2Xd probes = points_in_hull(pairs, 200, 17);
  for (Eigen::Index i = 0; i < probes.cols(); ++i) {
    ASSERT_EQ(loaded->forward(probes.col(i)), m->forward(probes.col(i))) << GetParam().name;
    ASSERT_EQ(loaded->predictive_std(probes.col(i)), m->predictive_std(probes.col(i)));
    ASSERT_EQ(loaded->nearest_pair_in_plan(probes.col(i)), m->nearest_pair_in_plan(probes.col(i)));
  }
  EXPECT_EQ(loaded->map_forward({-100.0, -100.0}).flag, MapFlag::outside_hull);
}

TEST_P(MappingContract, BadPairsGiveClearErrors) {
  MappingOptions options;
  options.model = GetParam().name;
  const Truth truth = test::similarity(0.1, 1.0, {1.0, 1.0});
  const auto expect_error = [&](const ReferencePairs& pairs, const std::string& part) {
    auto m = make_mapping(options);
    try {
      m->fit(pairs);
      ADD_FAILURE() << GetParam().name << ": no error for " << part;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "pairs") << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  auto m = make_mapping(options);
  const int needed = static_cast<int>(m->min_pairs());
  expect_error(make_pairs(random_points(needed - 1, 18), truth, 0.0, 19), "at least");
  ReferencePairs nan = make_pairs(random_points(50, 20), truth, 0.0, 21);
  nan.points_in_grid(1, 7) = std::numeric_limits<double>::quiet_NaN();
  expect_error(nan, "pair 8");
  if (m->needs_non_collinear()) {
    Eigen::Matrix2Xd line(2, 50);
    for (int i = 0; i < 50; ++i)
      line.col(i) << i * 0.7, 3.0 + i * 0.35;
    expect_error(make_pairs(line, truth, 0.0, 22), "line");
  }
}

TEST_P(MappingContract, DuplicatesMergeAndConflictsStayFinite) {
  ReferencePairs pairs = make_pairs(random_points(300, 23), test::bent(), 0.01, 24);
  // Exact duplicates and one conflicting duplicate (same plan point, grid 30 m away).
  ReferencePairs more;
  more.points_in_plan.resize(2, 303);
  more.points_in_grid.resize(2, 303);
  more.points_in_plan << pairs.points_in_plan, pairs.points_in_plan.leftCols(3);
  more.points_in_grid << pairs.points_in_grid, pairs.points_in_grid.leftCols(2),
      pairs.points_in_grid.col(2) + Eigen::Vector2d(30.0, 0.0);
  MappingOptions options;
  options.model = GetParam().name;
  auto m = make_mapping(options);
  const FitSummary s = m->fit(more);
  EXPECT_EQ(s.pairs_merged, 3u);
  EXPECT_EQ(s.pairs_conflicting, 1u);
  EXPECT_FALSE(s.warnings.empty());
  for (const auto& p :
       {Eigen::Vector2d(pairs.points_in_plan.col(2)), Eigen::Vector2d(20.0, 10.0)}) {
    EXPECT_TRUE(m->forward(p).allFinite()) << GetParam().name;
  }
}

TEST_P(MappingContract, ConfidenceFlagsTellHowFarToTrust) {
  const ReferencePairs pairs = make_pairs(random_points(400, 25), test::bent(), 0.0, 26);
  const auto m = fitted(GetParam().name, pairs);
  const Eigen::Vector2d on_pair = pairs.points_in_plan.col(0);
  EXPECT_LE(m->map_forward(on_pair).nearest_pair_m, 0.5);  // support binning may move it a little
  EXPECT_EQ(m->map_forward({20.0, 10.0}).flag, MapFlag::ok);
  const MappedPoint far = m->map_forward({80.0, 10.0});
  EXPECT_EQ(far.flag, MapFlag::outside_hull);
  EXPECT_NEAR(
      far.nearest_pair_m,
      (pairs.points_in_plan.colwise() - Eigen::Vector2d(80.0, 10.0)).colwise().norm().minCoeff(),
      1.0);
}

std::string model_test_name(const ::testing::TestParamInfo<Model>& param_info) {
  std::string name = param_info.param.name;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Models, MappingContract, ::testing::ValuesIn(all_models()),
                         model_test_name);
INSTANTIATE_TEST_SUITE_P(Models, ExactModels,
                         ::testing::ValuesIn(models_where(&ModelTraits::exact_similarity)),
                         model_test_name);
INSTANTIATE_TEST_SUITE_P(Models, NonRigidModels,
                         ::testing::ValuesIn(models_where(&ModelTraits::non_rigid)),
                         model_test_name);

TEST(GlobalTransformModel, SixtyPercentOutliersStillRecoverTheTransform) {
  const Truth truth = test::similarity(-1.2, 0.95, {8.0, 3.0});
  ReferencePairs pairs = make_pairs(random_points(1000, 27), truth, 0.01, 28);
  Random r(29);
  for (Eigen::Index i = 0; i < 600; ++i) {
    pairs.points_in_grid.col(i) << r.uniform(-30, 50), r.uniform(-30, 40);
  }
  const auto m = fitted("gt", pairs);
  ASSERT_TRUE(m->summary().inliers.has_value());
  EXPECT_NEAR(static_cast<double>(*m->summary().inliers), 400.0, 40.0);
  EXPECT_LE(max_error(*m, points_in_hull(pairs, 1000, 30), truth), 0.01);
}

}  // namespace
}  // namespace floorgrid
