// One contract for every observation model (the thesis's beam model and the likelihood field),
// on one shared fixture: a room without symmetry and a scan taken in it from a known pose.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

/// The shared fixture: the room as a grid and a scan from `kTruth`.
struct Fixture {
  static constexpr Pose2 kTruth{4.5, 5.2, 0.3};
  VectorFloorplan room = test::asymmetric_room();
  OccupancyGrid grid = test::room_grid(room);
  RobotLog log = test::log_along(room, {kTruth});
  ScanObservation scan = make_observation(log.scans[0], {.max_beams = 90});
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

template <typename Model>
class ObservationModelContract : public ::testing::Test {
 protected:
  Model model{fixture().grid};

  /// Log-likelihoods of the scan at `poses` (scale 1 unless the set carries scales).
  std::vector<double> scores(const ParticleSet& particles, int threads = 1) const {
    std::vector<double> out;
    model.log_likelihood(fixture().scan, particles, out, threads);
    return out;
  }
};

ParticleSet poses(std::initializer_list<Pose2> list) {
  ParticleSet set;
  for (const Pose2& p : list) {
    set.x.push_back(p.x);
    set.y.push_back(p.y);
    set.theta.push_back(p.theta);
    set.weight.push_back(1.0 / static_cast<double>(list.size()));
  }
  return set;
}

using Models = ::testing::Types<LikelihoodFieldModel, BeamModel>;
/// Test names say which model: ObservationModelContract/beam.ThreadsDoNotChangeTheScores.
struct ModelNames {
  template <typename T>
  static std::string GetName(int) {
    return std::is_same_v<T, BeamModel> ? "beam" : "likelihood_field";
  }
};
TYPED_TEST_SUITE(ObservationModelContract, Models, ModelNames);

TYPED_TEST(ObservationModelContract, TheTruePoseScoresAboveItsNeighbours) {
  const Pose2 t = Fixture::kTruth;
  const std::vector<double> s =
      this->scores(poses({t, t.compose({0.3, 0.0, 0.0}), t.compose({0.0, -0.3, 0.0}),
                          t.compose({0, 0, 0.2}), t.compose({0, 0, -0.2})}));
  for (std::size_t i = 1; i < s.size(); ++i)
    EXPECT_GT(s[0], s[i]) << "offset " << i;
  // The share of the scan explained at the truth is high, away from it lower.
  const double at_truth = this->model.mean_beam_likelihood(fixture().scan, t);
  EXPECT_GT(at_truth, 0.6);
  EXPECT_GT(at_truth, this->model.mean_beam_likelihood(fixture().scan, t.compose({0.5, 0, 0})));
}

TYPED_TEST(ObservationModelContract, ScoresStayFiniteOffTheMap) {
  const std::vector<double> s =
      this->scores(poses({{-100.0, -100.0, 0.0}, {1e4, 3.0, 1.0}, {6.0, 1e4, -2.0}}));
  for (const double v : s)
    EXPECT_TRUE(std::isfinite(v)) << v;
}

TYPED_TEST(ObservationModelContract, AScanWithoutReturnsChangesNothing) {
  const ScanObservation empty;
  std::vector<double> out;
  this->model.log_likelihood(empty, poses({Fixture::kTruth, {2.0, 2.0, 1.0}}), out, 1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], out[1]);  // no evidence prefers no pose
}

TYPED_TEST(ObservationModelContract, AScaledParticleSeesTheScanDividedByItsScale) {
  // The room drawn at 1 / 1.2 of the world: a particle with scale 1.2 at the scaled truth
  // explains the scan as well as a scale-1 particle at the truth explains it in the real room.
  VectorFloorplan small;
  for (const Segment& s : fixture().room.segments())
    small.add_segment(s.a / 1.2, s.b / 1.2, "W");
  const OccupancyGrid grid = test::room_grid(small);
  const TypeParam scaled_model(grid);
  ParticleSet scaled = poses({{Fixture::kTruth.x / 1.2, Fixture::kTruth.y / 1.2, 0.3},
                              {Fixture::kTruth.x / 1.2, Fixture::kTruth.y / 1.2, 0.3}});
  scaled.scale = {1.2, 1.0};
  std::vector<double> out;
  scaled_model.log_likelihood(fixture().scan, scaled, out, 1);
  EXPECT_GT(out[0], out[1]) << "the right scale must fit better than scale 1";
  const double fit = scaled_model.mean_beam_likelihood(
      fixture().scan, {Fixture::kTruth.x / 1.2, Fixture::kTruth.y / 1.2, 0.3}, 1.2);
  EXPECT_NEAR(fit, this->model.mean_beam_likelihood(fixture().scan, Fixture::kTruth), 0.15);
}

TYPED_TEST(ObservationModelContract, ThreadsDoNotChangeTheScores) {
  ParticleSet many;
  Random random(2);
  for (int i = 0; i < 3000; ++i) {
    many.x.push_back(random.uniform(0.5, 11.5));
    many.y.push_back(random.uniform(0.5, 7.5));
    many.theta.push_back(random.uniform(-3.0, 3.0));
    many.weight.push_back(1.0 / 3000);
  }
  EXPECT_EQ(this->scores(many, 1), this->scores(many, 2));
}

}  // namespace
}  // namespace floorgrid
