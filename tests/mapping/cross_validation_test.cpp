// Spatially blocked cross-validation: the partition (whole blocks per fold, deterministic for a
// seed) and what it measures, on a case whose truth is known: dense near-copies of noisy pairs,
// where random k-fold credits an interpolator with the noise it copies and blocked folds do not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "floorgrid/core/random.hpp"
#include "floorgrid/localization/pair_extraction.hpp"
#include "floorgrid/mapping/cross_validation_folds.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_selection.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"
#include "tests/mapping/mapping_test_data.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

/// The square of `size` metres, counted from `lower`, holding `p`.
std::pair<long, long> cell_of(const Eigen::Vector2d& p, const Eigen::Vector2d& lower, double size) {
  return {static_cast<long>(std::floor((p.x() - lower.x()) / size)),
          static_cast<long>(std::floor((p.y() - lower.y()) / size))};
}

TEST(BlockedFolds, EveryFoldHoldsOutWholeSquareBlocks) {
  const Eigen::Matrix2Xd points = test::random_points(3000, 5);
  const double size = 4.0;
  const Folds folds = blocked_folds(points, 5, size, 7);
  ASSERT_EQ(folds.count, 5u);
  ASSERT_EQ(folds.fold_of.size(), 3000u);
  EXPECT_EQ(folds.block_size, size);
  const Eigen::Vector2d lower = points.rowwise().minCoeff();
  // A block is exactly the points of one square: same square, same block, and back.
  std::map<std::pair<long, long>, std::size_t> block_of_cell;
  std::map<std::size_t, std::size_t> fold_of_block;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const auto cell = cell_of(points.col(i), lower, size);
    const std::size_t block = folds.block_of[static_cast<std::size_t>(i)];
    const auto [at, inserted] = block_of_cell.emplace(cell, block);
    EXPECT_EQ(at->second, block) << "one square split into blocks";
    // Every point of a block is in the same fold: held out whole.
    const auto [f, new_block] =
        fold_of_block.emplace(block, folds.fold_of[static_cast<std::size_t>(i)]);
    EXPECT_EQ(f->second, folds.fold_of[static_cast<std::size_t>(i)]) << "block split by folds";
  }
  EXPECT_EQ(block_of_cell.size(), folds.blocks);
  std::set<std::size_t> blocks;
  for (const auto& [cell, block] : block_of_cell)
    blocks.insert(block);
  EXPECT_EQ(blocks.size(), folds.blocks) << "two squares share a block";
  // So no held-out point shares its square with a training point, and the folds are of similar
  // size (within a block's worth: about 3000 / 50 points here).
  std::vector<std::size_t> sizes(folds.count, 0);
  for (const std::size_t f : folds.fold_of)
    ++sizes[f];
  for (const std::size_t s : sizes) {
    EXPECT_GT(s, 500u);
    EXPECT_LT(s, 700u);
  }
}

TEST(BlockedFolds, TheSameSeedGivesTheSameFoldsWhateverThePairsOrder) {
  const Eigen::Matrix2Xd points = test::random_points(2000, 9);
  const Folds a = blocked_folds(points, 5, 3.0, 11);
  EXPECT_EQ(blocked_folds(points, 5, 3.0, 11).fold_of, a.fold_of);
  EXPECT_NE(blocked_folds(points, 5, 3.0, 12).fold_of, a.fold_of);
  // Reversed, each point keeps its fold: blocks are numbered by place, not by arrival.
  const Eigen::Matrix2Xd reversed = points.rowwise().reverse();
  const Folds b = blocked_folds(reversed, 5, 3.0, 11);
  for (std::size_t i = 0; i < a.fold_of.size(); ++i)
    EXPECT_EQ(b.fold_of[a.fold_of.size() - 1 - i], a.fold_of[i]);
}

TEST(BlockedFolds, FewerBlocksThanFoldsGiveOneFoldPerBlock) {
  Eigen::Matrix2Xd points(2, 4);
  points << 0.1, 0.2, 5.1, 5.2,  //
      0.1, 0.3, 0.1, 0.2;
  const Folds folds = blocked_folds(points, 5, 4.0, 1);
  EXPECT_EQ(folds.blocks, 2u);
  EXPECT_EQ(folds.count, 2u);
  EXPECT_EQ(folds.fold_of[0], folds.fold_of[1]);
  EXPECT_EQ(folds.fold_of[2], folds.fold_of[3]);
  EXPECT_NE(folds.fold_of[0], folds.fold_of[2]);
}

TEST(RandomFolds, DealsThePairsEvenlyAndDeterministically) {
  const Folds folds = random_folds(103, 5, 3);
  ASSERT_EQ(folds.count, 5u);
  EXPECT_EQ(folds.block_size, 0.0);
  std::vector<std::size_t> sizes(5, 0);
  for (const std::size_t f : folds.fold_of)
    ++sizes[f];
  for (const std::size_t s : sizes)
    EXPECT_TRUE(s == 20u || s == 21u) << s;
  EXPECT_EQ(random_folds(103, 5, 3).fold_of, folds.fold_of);
  EXPECT_EQ(random_folds(3, 5, 3).count, 3u);
  // Dealt round robin in a shuffled order, which lists every pair once.
  std::vector<std::size_t> order = folds.order;
  for (std::size_t i = 0; i < order.size(); ++i)
    EXPECT_EQ(folds.fold_of[order[i]], i % 5);
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < order.size(); ++i)
    EXPECT_EQ(order[i], i);
}

TEST(BlockSize, AFewMetresOnABuildingSmallerOnASmallSetNeverBelowThePairSpacing) {
  // A 40 x 20 m building with dense pairs: the largest automatic block.
  EXPECT_EQ(choose_block_size(test::random_points(3000, 1), 5), kLargestAutoBlock);
  // A 6 x 6 m room: shrunk until there are 4 blocks per fold.
  const Eigen::Matrix2Xd room = test::random_points(2000, 2).array() * 0.15;
  const double size = choose_block_size(room, 5);
  EXPECT_LT(size, kLargestAutoBlock);
  EXPECT_GE(blocked_folds(room, 5, size, 1).blocks, kAutoBlocksPerFold * 5);
  // Ten points 1 m apart on a line: not below twice their spacing.
  Eigen::Matrix2Xd line(2, 10);
  for (int i = 0; i < 10; ++i)
    line.col(i) << i, 0.0;
  EXPECT_GE(choose_block_size(line, 5), 2.0);
}

/// The analytic case: the truth is the identity; 400 places 1 m apart each carry an offset
/// drawn from N(0, sigma^2 I) shared by 3 near-copies within 2 cm of one another, as laser pairs
/// share a scan's pose error (1200 pairs: within every pair budget, so nothing is binned). A model
/// not fitted on a pair's own place cannot know its offset: its expected error there is at least
/// E|offset| = sigma sqrt(pi / 2) (the mean of a Rayleigh distribution; c -> E|b - c| is least at
/// the centre c = 0 of a symmetric b).
struct NearCopies {
  ReferencePairs pairs;
  double sigma = 0.05;
};

NearCopies near_copies() {
  NearCopies c;
  Random random(21);
  const int places = 20, copies = 3;
  c.pairs.points_in_plan.resize(2, places * places * copies);
  c.pairs.points_in_grid.resize(2, places * places * copies);
  Eigen::Index k = 0;
  for (int i = 0; i < places; ++i) {
    for (int j = 0; j < places; ++j) {
      const Eigen::Vector2d place(i + random.uniform(0.2, 0.8), j + random.uniform(0.2, 0.8));
      const Eigen::Vector2d offset(random.normal(c.sigma), random.normal(c.sigma));
      for (int n = 0; n < copies; ++n, ++k) {
        const Eigen::Vector2d p =
            place + Eigen::Vector2d(random.uniform(-0.01, 0.01), random.uniform(-0.01, 0.01));
        c.pairs.points_in_plan.col(k) = p;
        c.pairs.points_in_grid.col(k) = p + offset;
      }
    }
  }
  return c;
}

TEST(BlockedCrossValidation, DoesNotCreditAnInterpolatorWithTheNoiseItsNearCopiesCarry) {
  const NearCopies c = near_copies();
  const double floor_m = c.sigma * std::sqrt(std::numbers::pi / 2.0);  // 0.0627 m
  MappingOptions dt;
  dt.model = "dt";
  CrossValidationOptions random;
  random.kind = CrossValidationKind::random;
  CrossValidationOptions blocked;  // the default
  blocked.block_size = 3.0;
  // Random folds: a held-out pair's near-copies are in training, the triangulation passes
  // through them, and the error looks like a fraction of the noise.
  const CrossValidationResult r = cross_validate(dt, c.pairs, random);
  EXPECT_LT(r.mean_error_m, 0.3 * floor_m);
  EXPECT_EQ(r.method.kind, "random");
  EXPECT_EQ(r.method.block_size, 0.0);
  // Blocked folds: whole 3 m blocks held out, so no copy of a held-out offset is in training
  // (but for the rare place on a block's edge), and the error cannot beat the floor.
  const CrossValidationResult b = cross_validate(dt, c.pairs, blocked);
  EXPECT_GT(b.mean_error_m, 0.95 * floor_m);
  EXPECT_EQ(b.method.kind, "blocked");
  EXPECT_EQ(b.method.block_size, 3.0);
  EXPECT_EQ(b.method.folds, 5u);
  EXPECT_EQ(b.method.pairs, 1200u);
  // The true model (a similarity) is near the floor under blocked folds; random folds rank the
  // interpolator first, blocked folds the truth.
  MappingOptions gt;
  gt.model = "gt";
  const double gt_blocked = cross_validate(gt, c.pairs, blocked).mean_error_m;
  EXPECT_LT(gt_blocked, 1.1 * floor_m);
  EXPECT_LT(r.mean_error_m, cross_validate(gt, c.pairs, random).mean_error_m);
  EXPECT_LT(gt_blocked, b.mean_error_m);
}

TEST(BlockedCrossValidation, AutoPicksTheTruthWhereRandomFoldsPickTheInterpolator) {
  const NearCopies c = near_copies();
  MappingOptions options;
  options.model = "auto";
  options.auto_select.candidates = {"gt", "dt"};
  auto blocked = make_mapping(options);
  blocked->fit(c.pairs);
  EXPECT_EQ(blocked->summary().details.find("chosen")->as_string(), "gt");
  ASSERT_TRUE(blocked->summary().cv.has_value());
  EXPECT_EQ(blocked->summary().cv->kind, "blocked");
  EXPECT_GT(blocked->summary().cv->block_size, 0.0);  // chosen from the pairs
  options.auto_select.cv.kind = CrossValidationKind::random;
  auto random = make_mapping(options);
  random->fit(c.pairs);
  EXPECT_EQ(random->summary().details.find("chosen")->as_string(), "dt");
  EXPECT_EQ(random->summary().cv->kind, "random");
}

TEST(RunFolds, StretchesOfThePairsOrderTakeTurnsInTheFolds) {
  const Folds folds = run_folds(1000, 5, 3);
  ASSERT_EQ(folds.count, 5u);
  ASSERT_EQ(folds.fold_of.size(), 1000u);
  // 15 stretches of 66-67 pairs: pair i in stretch floor(15 i / 1000), its fold that mod 5.
  std::size_t changes = 0;
  for (std::size_t i = 0; i < 1000; ++i) {
    EXPECT_EQ(folds.fold_of[i], (15 * i / 1000) % 5) << i;
    changes += i > 0 && folds.fold_of[i] != folds.fold_of[i - 1];
  }
  EXPECT_EQ(changes, 14u);
  EXPECT_EQ(run_folds(3, 5, 3).count, 3u);
}

TEST(ThinInOrder, KeepsEvenlySpreadPairsInTheirOrder) {
  const ReferencePairs pairs =
      test::make_pairs(test::random_points(1000, 3), test::similarity(0.1, 1.0, {1, 2}), 0.0, 4);
  const ReferencePairs thin = thin_in_order(pairs, 300);
  ASSERT_EQ(thin.size(), 300);
  for (Eigen::Index k = 0; k < 300; ++k)
    EXPECT_EQ(thin.points_in_plan.col(k), pairs.points_in_plan.col(k * 1000 / 300)) << k;
  EXPECT_EQ(thin_in_order(pairs, 2000).size(), 1000);
}

/// A run's pairs: a robot passing twice along a 40 m loop of corridor, 20 pairs a scan every
/// 0.5 m, the grid the plan through a similarity, each pair off by its scan's pose error. The
/// pose error wanders (a random walk of 2 cm a scan, as the filters' errors drift along a run)
/// and the two passes' errors are independent. The truth is the similarity: a model that bends
/// to follow one pass's error is wrong by it, on the walls both passes saw.
ReferencePairs two_passes() {
  Random random(8);
  const test::Truth truth = test::similarity(0.3, 1.2, {2.0, -1.0});
  PairCollector pairs;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Vector2d error = Eigen::Vector2d::Zero();
    for (int scan = 0; scan < 80; ++scan) {
      error += Eigen::Vector2d(random.normal(0.02), random.normal(0.02));
      error *= 0.95;                // it stays bounded, about 7 cm
      const double u = 0.5 * scan;  // metres along the loop: a 10 m x 10 m square
      const double along = std::fmod(u + 0.25 * pass, 40.0);
      Eigen::Vector2d robot = along < 10   ? Eigen::Vector2d(along, 0.0)
                              : along < 20 ? Eigen::Vector2d(10.0, along - 10.0)
                              : along < 30 ? Eigen::Vector2d(30.0 - along, 10.0)
                                           : Eigen::Vector2d(0.0, 40.0 - along);
      for (int k = 0; k < 20; ++k) {
        // Walls 1 m either side of the corridor, seen up to 2 m ahead and behind.
        const Eigen::Vector2d p =
            robot + Eigen::Vector2d(random.uniform(-2.0, 2.0), k % 2 == 0 ? -1.0 : 1.0);
        pairs.plan.push_back(p);
        pairs.grid.push_back(truth(p) + error +
                             Eigen::Vector2d(random.normal(0.005), random.normal(0.005)));
      }
    }
  }
  return pairs.pairs();
}

TEST(RunsCrossValidation, AutoPicksTheTruthWhereRandomFoldsPickTheInterpolator) {
  const ReferencePairs pairs = two_passes();
  MappingOptions options;
  options.model = "auto";
  options.auto_select.candidates = {"gt", "dt"};
  // Random folds: a held-out pair's scan siblings are in training, carrying its error.
  options.auto_select.cv.kind = CrossValidationKind::random;
  auto random = make_mapping(options);
  random->fit(pairs);
  EXPECT_EQ(random->summary().details.find("chosen")->as_string(), "dt");
  // Runs: a held-out stretch is predicted from the other pass and the other stretches.
  options.auto_select.cv.kind = CrossValidationKind::runs;
  auto runs = make_mapping(options);
  runs->fit(pairs);
  EXPECT_EQ(runs->summary().details.find("chosen")->as_string(), "gt");
  ASSERT_TRUE(runs->summary().cv.has_value());
  EXPECT_EQ(runs->summary().cv->kind, "runs");
  EXPECT_EQ(runs->summary().cv->pairs, 3000u);  // thinned along the run to the budget
  // The chosen model's std_m still comes from blocked folds.
  EXPECT_TRUE(runs->error_model().has_value());
}

/// Held-out errors of 100 pairs: `good` on the first 90, `bad` on a stretch of 10.
CrossValidationResult held_out_errors(double good, double bad) {
  CrossValidationResult cv;
  cv.pair_errors.assign(90, good);
  cv.pair_errors.insert(cv.pair_errors.end(), 10, bad);
  cv.mean_error_m = (90 * good + 10 * bad) / 100.0;
  cv.median_error_m = good;
  return cv;
}

TEST(PairedScores, TrimTheStretchEveryModelGotWrongAndCompareSquaredErrors) {
  // gt errs little but on the stretch the filters got wrong, dt a little everywhere.
  const CrossValidationResult gt = held_out_errors(0.02, 0.8), dt = held_out_errors(0.04, 0.5);
  const std::vector<double> scores = paired_scores({gt.pair_errors, dt.pair_errors});
  ASSERT_EQ(scores.size(), 2u);
  EXPECT_NEAR(scores[0], 0.02 * 0.02, 1e-12);  // the stretch trimmed
  EXPECT_NEAR(scores[1], 0.04 * 0.04, 1e-12);
  // Untrimmed, the stretch decides.
  const std::vector<double> all = paired_scores({gt.pair_errors, dt.pair_errors}, 1e9);
  EXPECT_GT(all[0], all[1]);
  // Squared errors, not medians: errors of 0.01 and 0.03 half and half score below 0.025
  // everywhere (mean squared 0.0005 < 0.000625), though their median is larger.
  std::vector<double> mixed(100, 0.01), flat(100, 0.025);
  std::fill(mixed.begin(), mixed.begin() + 50, 0.03);
  const std::vector<double> noise = paired_scores({mixed, flat});
  EXPECT_LT(noise[0], noise[1]);
  // A model that could not predict a kept pair scores infinite; sizes that differ too.
  std::vector<double> failed = flat;
  failed[3] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isinf(paired_scores({flat, failed})[1]));
  EXPECT_TRUE(std::isinf(paired_scores({flat, {0.1, 0.2}})[1]));
  EXPECT_TRUE(paired_scores({}).empty());
}

TEST(RunsCrossValidation, AutoPicksByPairedScoresAndOtherwiseByTheMean) {
  const CrossValidationResult gt = held_out_errors(0.02, 0.8), dt = held_out_errors(0.04, 0.5);
  MappingOptions options;
  options.model = "auto";
  options.auto_select.candidates = {"gt", "dt"};
  const auto chosen = [&](CrossValidationKind kind) {
    options.auto_select.cv.kind = kind;
    auto model = make_mapping(options);
    dynamic_cast<AutoMapping&>(*model).reuse_cross_validation({{"gt", gt}, {"dt", dt}});
    model->fit(two_passes());
    return model->summary().details.find("chosen")->as_string();
  };
  EXPECT_EQ(chosen(CrossValidationKind::runs), "gt");
  EXPECT_EQ(chosen(CrossValidationKind::blocked), "dt");
}

// The standard error of a paired difference, against hand-computed cases: a difference the
// same on every stretch has none; stretches of m pairs alternating +x and -x (mean 0) have
// sqrt(C (m x)^2 C / (C - 1)) / (C m) = x / sqrt(C - 1) over C stretches.
TEST(PairedScores, TheStandardErrorOfADifferenceComesFromItsSpreadOverStretches) {
  const std::vector<char> all(100, 1);
  const std::vector<double> a(100, 0.04), b(100, 0.03);
  EXPECT_NEAR(paired_score_difference_se(a, b, all, 4), 0.0, 1e-15);
  // Stretches of 25 pairs whose differences of squares are +x, -x, +x, -x.
  const double x = 0.04 * 0.04 - 0.03 * 0.03;
  std::vector<double> alternating(100);
  for (std::size_t i = 0; i < 100; ++i)
    alternating[i] = (i / 25) % 2 == 0 ? 0.04 : std::sqrt(0.03 * 0.03 - x);
  EXPECT_NEAR(paired_score_difference_se(alternating, b, all, 4), x / std::sqrt(3.0), 1e-12);
  // Pairs left out do not count: the first two stretches kept, one +x and one -x.
  std::vector<char> half(100, 0);
  std::fill(half.begin(), half.begin() + 50, 1);
  EXPECT_NEAR(paired_score_difference_se(alternating, b, half, 4), x, 1e-12);
  // Undefined: one stretch, sizes that differ, an infinite error on a kept pair.
  EXPECT_TRUE(std::isinf(paired_score_difference_se(a, b, all, 1)));
  EXPECT_TRUE(std::isinf(paired_score_difference_se(a, {0.1}, all, 4)));
  std::vector<double> failed = a;
  failed[7] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isinf(paired_score_difference_se(failed, b, all, 4)));
}

// One standard error: an earlier candidate whose paired score is above the lowest by less than
// the noise of that difference is chosen; by more, or with the rule off, the lowest.
TEST(RunsCrossValidation, AutoKeepsTheEarlierCandidateWithinOneStandardError) {
  // 200 pairs in run order; dt errs 0.032 everywhere; gt's squared error is dt's plus 2e-5,
  // plus or minus 3e-4 by stretches of 10 pairs: dt scores lower, by much less than the
  // stretches' spread (its standard error is about 3e-4 / sqrt(39) = 4.8e-5).
  const double dt_square = 0.032 * 0.032;
  CrossValidationResult gt, dt;
  for (std::size_t i = 0; i < 200; ++i) {
    gt.pair_errors.push_back(std::sqrt(dt_square + 2e-5 + ((i / 10) % 2 == 0 ? 3e-4 : -3e-4)));
    dt.pair_errors.push_back(0.032);
  }
  gt.mean_error_m = dt.mean_error_m = 0.032;
  const std::vector<double> scores = paired_scores({gt.pair_errors, dt.pair_errors});
  ASSERT_NEAR(scores[0] - scores[1], 2e-5, 1e-12);
  MappingOptions options;
  options.model = "auto";
  options.auto_select.candidates = {"gt", "dt"};
  options.auto_select.cv.kind = CrossValidationKind::runs;
  const auto chosen = [&](double tie_standard_errors, const CrossValidationResult& first) {
    options.auto_select.tie_standard_errors = tie_standard_errors;
    auto model = make_mapping(options);
    dynamic_cast<AutoMapping&>(*model).reuse_cross_validation({{"gt", first}, {"dt", dt}});
    model->fit(two_passes());
    return model->summary().details.find("chosen")->as_string();
  };
  EXPECT_EQ(chosen(1.0, gt), "gt");
  EXPECT_EQ(chosen(0.0, gt), "dt");
  // gt worse by the same margin on every pair: no noise hides it, dt.
  CrossValidationResult steady = gt;
  std::fill(steady.pair_errors.begin(), steady.pair_errors.end(), std::sqrt(dt_square + 2e-5));
  EXPECT_EQ(chosen(1.0, steady), "dt");
  options.auto_select.tie_standard_errors = -1.0;
  test::expect_input_error([&] { make_mapping(options); }, {"auto_select.tie_standard_errors"});
}

TEST(BlockedCrossValidation, RefusesANegativeBlockAndTooFewFolds) {
  MappingOptions gt;
  gt.model = "gt";
  const ReferencePairs pairs =
      test::make_pairs(test::random_points(100, 3), test::similarity(0.1, 1.0, {1, 2}), 0.01, 4);
  CrossValidationOptions cv;
  cv.block_size = -1.0;
  test::expect_input_error([&] { cross_validate(gt, pairs, cv); }, {"cv.block_size"});
  cv.block_size = 0.0;
  cv.folds = 1;
  test::expect_input_error([&] { cross_validate(gt, pairs, cv); }, {"cv.folds"});
  MappingOptions chooser;
  chooser.model = "auto";
  chooser.auto_select.cv.block_size = -2.0;
  test::expect_input_error([&] { make_mapping(chooser); }, {"auto_select.cv.block_size"});
}

}  // namespace
}  // namespace floorgrid
