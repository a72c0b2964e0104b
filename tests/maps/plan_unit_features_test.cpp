// Unit-free features of a drawing that tell its units: door leaves, wall bands, core extent.

#include "floorgrid/maps/plan_unit_features.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace floorgrid {
namespace {

constexpr double kPi = std::numbers::pi;

/// A door swing about `hinge`: a quarter arc from `start` and its leaf along the arc's end.
void add_swing(std::vector<PlanCircle>& arcs, std::vector<PlanLine>& lines,
               const Eigen::Vector2d& hinge, double radius, double start) {
  arcs.push_back({hinge, radius, start, start + kPi / 2});
  lines.push_back({hinge, hinge + radius * Eigen::Vector2d(std::cos(start + kPi / 2),
                                                           std::sin(start + kPi / 2))});
}

/// A wall along x from x0 to x1 at height y, `t` thick, as its two faces.
void add_wall(std::vector<PlanLine>& lines, double x0, double x1, double y, double t) {
  lines.push_back({{x0, y - t / 2}, {x1, y - t / 2}});
  lines.push_back({{x0, y + t / 2}, {x1, y + t / 2}});
}

std::vector<PlanLine> scaled(std::vector<PlanLine> lines, double k) {
  for (PlanLine& l : lines) {
    l.a *= k;
    l.b *= k;
  }
  return lines;
}

TEST(PlanUnitFeatures, DoorLeavesAreLinesFromTheHingeTowardsAnArcEnd) {
  std::vector<PlanCircle> arcs;
  std::vector<PlanLine> lines;
  add_swing(arcs, lines, {0, 0}, 0.9, 0.0);      // leaf along the end
  arcs.push_back({{10, 0}, 0.9, 0.0, kPi / 2});  // leaf along the start, drawn backwards
  lines.push_back({{10.9, 0.0}, {10.01, 0.0}});
  arcs.push_back({{20, 0}, 0.9, 0.0, kPi / 2});  // a line from the hinge the wrong way
  lines.push_back({{20, 0}, {20 - 0.9, 0}});
  arcs.push_back({{30, 0}, 0.9, 0.0, kPi / 2});  // a line to the end, not from the hinge
  lines.push_back({{30.3, 0.3}, {30.0, 0.9}});
  arcs.push_back({{40, 0}, 0.9, 0.0, kPi / 2});  // a line from the hinge, far too short
  lines.push_back({{40, 0}, {40, 0.3}});
  arcs.push_back({{50, 0}, 0.9, 0.0, kPi});  // a half turn is never a swing
  lines.push_back({{50, 0}, {50.9, 0}});
  const std::vector<PlanArc> found = find_door_leaves(arcs, lines);
  ASSERT_EQ(found.size(), arcs.size());
  EXPECT_TRUE(found[0].leaf);
  EXPECT_TRUE(found[1].leaf);
  EXPECT_FALSE(found[2].leaf);
  EXPECT_FALSE(found[3].leaf);
  EXPECT_FALSE(found[4].leaf);
  EXPECT_FALSE(found[5].leaf);
  EXPECT_DOUBLE_EQ(found[0].radius, 0.9);
  EXPECT_DOUBLE_EQ(found[5].sweep, kPi);
}

TEST(PlanUnitFeatures, WallBandsGiveThicknessAndRoomSpacingInAnyUnit) {
  // Ten 0.2-thick walls 4 apart, each split into pieces as walls are at door openings.
  std::vector<PlanLine> lines;
  for (int i = 0; i < 10; ++i) {
    for (int piece = 0; piece < 5; ++piece) {
      add_wall(lines, 6.0 * piece, 6.0 * piece + 5.0, 4.2 * i, 0.2);
    }
  }
  const WallBandSummary m = measure_wall_bands(lines);
  EXPECT_EQ(m.faces, lines.size());
  EXPECT_NEAR(m.thickness, 0.2, 1e-9);
  EXPECT_GT(m.thickness_share, 0.99);
  EXPECT_NEAR(m.spacing, 4.0, 1e-9);
  // The same in millimetres, and turned by 30 degrees: the rules are ratios and angles.
  std::vector<PlanLine> turned = scaled(lines, 1000.0);
  const Eigen::Rotation2Dd R(kPi / 6);
  for (PlanLine& l : turned) {
    l.a = R * l.a;
    l.b = R * l.b;
  }
  const WallBandSummary mm = measure_wall_bands(turned);
  EXPECT_EQ(mm.faces, m.faces);
  EXPECT_NEAR(mm.thickness, 200.0, 1e-6);
  EXPECT_NEAR(mm.spacing, 4000.0, 1e-6);
}

TEST(PlanUnitFeatures, EvenlySpacedLinesAreNoWalls) {
  // Stair treads and single-line walls: neighbours as close on both sides.
  std::vector<PlanLine> lines;
  for (int i = 0; i < 30; ++i) {
    lines.push_back({{0.0, 0.3 * i}, {1.2, 0.3 * i}});
  }
  const WallBandSummary s = measure_wall_bands(lines);
  EXPECT_EQ(s.faces, 2u);  // only the first and last tread, with one neighbour
  EXPECT_TRUE(measure_wall_bands({}).faces == 0u);
}

TEST(PlanUnitFeatures, CollinearPiecesOfARegularBuildingDoNotHideTheOtherFace) {
  // 400 rooms in a row share one wall line: their wall pieces are collinear, and each face's
  // partner across the wall still has to be found among them.
  std::vector<PlanLine> lines;
  for (int room = 0; room < 400; ++room) {
    add_wall(lines, 5.0 * room, 5.0 * room + 4.8, 0.0, 0.15);
  }
  const WallBandSummary s = measure_wall_bands(lines);
  EXPECT_EQ(s.faces, lines.size());
  EXPECT_NEAR(s.thickness, 0.15, 1e-9);
}

TEST(PlanUnitFeatures, CoreExtentLeavesOutAFewFarOffStrays) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= 1000; ++i) {
    points.emplace_back(455000.0 + 0.34 * i, 5650000.0 + 0.206 * i);
  }
  points.emplace_back(0.0, 0.0);  // a survey marker at the origin
  const Eigen::AlignedBox2d core = core_extent(points);
  EXPECT_NEAR(core.sizes().x(), 340.0, 10.0);
  EXPECT_NEAR(core.sizes().y(), 206.0, 10.0);
  // A handful of points keeps them all.
  const Eigen::AlignedBox2d few = core_extent({{0, 0}, {3, 1}, {1, 4}});
  EXPECT_EQ(few.min(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(few.max(), Eigen::Vector2d(3, 4));
  EXPECT_TRUE(core_extent({}).isEmpty());
}

}  // namespace
}  // namespace floorgrid
