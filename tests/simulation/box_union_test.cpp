#include "floorgrid/simulation/box_union.hpp"

#include <gtest/gtest.h>

namespace floorgrid {
namespace {

Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1));
}

double total_length(const std::vector<Segment>& edges) {
  double total = 0;
  for (const auto& s : edges)
    total += s.length();
  return total;
}

TEST(BoxUnion, SingleBoxIsItsFourSides) {
  const auto out = box_union_outline({box(0, 0, 2, 1)});
  EXPECT_EQ(out.edges.size(), 4u);
  EXPECT_DOUBLE_EQ(total_length(out.edges), 6.0);
  EXPECT_EQ(out.corners.size(), 4u);
}

TEST(BoxUnion, OverlappingAndTouchingBoxesMerge) {
  // An L from two overlapping boxes, plus a box touching its end: perimeter of the union.
  const auto out = box_union_outline({box(0, 0, 4, 1), box(0, 0, 1, 3), box(4, 0, 5, 1)});
  // The union is an L: 5 x 1 along x and 1 x 3 along y. Perimeter = 2 * (5 + 3) = 16.
  EXPECT_DOUBLE_EQ(total_length(out.edges), 16.0);
  EXPECT_EQ(out.edges.size(), 6u);  // collinear pieces merged
  EXPECT_EQ(out.corners.size(), 6u);
  // Every edge keeps the inside on its left: the signed area is positive and equals 5 + 2.
  double area = 0;
  for (const auto& s : out.edges)
    area += 0.5 * (s.a.x() * s.b.y() - s.b.x() * s.a.y());
  EXPECT_DOUBLE_EQ(area, 7.0);
}

TEST(BoxUnion, RingHasInnerOutline) {
  // A square ring: outer 4 x 4, hole 2 x 2.
  const auto out =
      box_union_outline({box(0, 0, 4, 1), box(0, 3, 4, 4), box(0, 0, 1, 4), box(3, 0, 4, 4)});
  EXPECT_DOUBLE_EQ(total_length(out.edges), 16.0 + 8.0);
  double area = 0;
  for (const auto& s : out.edges)
    area += 0.5 * (s.a.x() * s.b.y() - s.b.x() * s.a.y());
  EXPECT_DOUBLE_EQ(area, 16.0 - 4.0);
  EXPECT_TRUE(inside_any({box(0, 0, 4, 1)}, {2.0, 0.5}));
  EXPECT_FALSE(inside_any({box(0, 0, 4, 1)}, {2.0, 1.5}));
}

}  // namespace
}  // namespace floorgrid
