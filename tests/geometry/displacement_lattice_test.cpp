// The displacement lattice recovers a known smooth field from directional observations.
#include "floorgrid/geometry/displacement_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace floorgrid {
namespace {

// A smooth field: a shift plus a gentle bend, metres.
Eigen::Vector2d field(const Eigen::Vector2d& p) {
  return {0.3 + 0.01 * p.y(), -0.2 + 0.2 * std::sin(p.x() / 10.0)};
}

TEST(DisplacementLattice, RecoversASmoothFieldFromObservationsAcrossRandomWalls) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(0, 0), Eigen::Vector2d(40, 30));
  DisplacementLattice lattice(box, 2.0);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(0, 40), y(0, 30), angle(0, 2 * M_PI);
  std::vector<LatticeConstraint> constraints;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector2d p(x(random), y(random));
    const double a = angle(random);
    const Eigen::Vector2d n(std::cos(a), std::sin(a));
    constraints.push_back({p, n, n.dot(field(p)), 1.0});
  }
  ASSERT_TRUE(lattice.fit(constraints, 0.01));
  double worst = 0.0;
  for (double px = 2; px <= 38; px += 3)
    for (double py = 2; py <= 28; py += 3)
      worst = std::max(worst, (lattice.at({px, py}) - field({px, py})).norm());
  // Bilinear over 2 m cells of a field that bends 0.2 m over 10 m: millimetres.
  EXPECT_LT(worst, 0.01);
}

TEST(DisplacementLattice, WallsAlongOneDirectionLeaveTheOtherToTheNeighbours) {
  // Only x is observed (walls across x) on the left half; the right half sees y only. The
  // membrane carries each side's motion over smoothly instead of leaving nodes undetermined.
  const Eigen::AlignedBox2d box(Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 10));
  DisplacementLattice lattice(box, 2.0);
  std::vector<LatticeConstraint> constraints;
  for (double px = 0.5; px < 20; px += 0.5) {
    for (double py = 0.5; py < 10; py += 0.5) {
      const Eigen::Vector2d n = px < 10 ? Eigen::Vector2d::UnitX() : Eigen::Vector2d::UnitY();
      constraints.push_back({{px, py}, n, n.dot(Eigen::Vector2d(0.1, -0.1)), 1.0});
    }
  }
  ASSERT_TRUE(lattice.fit(constraints, 0.1));
  // Each side's unobserved component takes the other side's value: the field is the one
  // constant motion both halves agree with.
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(3, 5), Eigen::Vector2d(17, 5)}) {
    EXPECT_NEAR(lattice.at(p).x(), 0.1, 0.01) << p.transpose();
    EXPECT_NEAR(lattice.at(p).y(), -0.1, 0.01) << p.transpose();
  }
}

TEST(DisplacementLattice, NoObservationLeavesTheFieldZero) {
  DisplacementLattice lattice(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(5, 5)),
                              1.0);
  EXPECT_FALSE(lattice.fit({}, 1.0));
  EXPECT_FALSE(lattice.fit({{{1, 1}, {1, 0}, 0.5, 0.0}}, 1.0));
  EXPECT_EQ(lattice.at({2, 2}), Eigen::Vector2d::Zero());
  EXPECT_EQ(lattice.columns(), 6);
  EXPECT_EQ(lattice.rows(), 6);
}

}  // namespace
}  // namespace floorgrid
