#include "floorgrid/simulation/segment_ray_caster.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "floorgrid/core/random.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

using Eigen::Vector2d;

Segment segment(double ax, double ay, double bx, double by, int layer = 0) {
  Segment s;
  s.a = {ax, ay};
  s.b = {bx, by};
  s.layer = layer;
  return s;
}

/// The reference: every segment through intersect_ray_segment, nearest first, ties to the lowest
/// index.
std::optional<RayHit> brute_force(const std::vector<Segment>& segments, const Vector2d& origin,
                                  const Vector2d& direction, double max_range) {
  std::optional<RayHit> best;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::optional<double> t =
        intersect_ray_segment(origin, direction, segments[i], max_range);
    if (t && (!best || *t < best->range))
      best = RayHit{*t, i, segments[i].layer};
  }
  return best;
}

/// A random scene of about `n` segments in [0, 30] x [0, 20] with the awkward cases mixed in:
/// axis-parallel segments on cell boundaries (integer coordinates), closed polygons sharing
/// corners, collinear overlapping pieces, duplicates and zero-length segments.
std::vector<Segment> random_scene(Random& random, int n) {
  std::vector<Segment> s;
  while (static_cast<int>(s.size()) < n) {
    const int layer = static_cast<int>(random.integer(0, 2));
    switch (random.integer(0, 6)) {
      case 0: {  // free segment of random length and direction
        const Vector2d a(random.uniform(0, 30), random.uniform(0, 20));
        const double len = random.uniform(0.05, 8.0), ang = random.uniform(-4, 4);
        s.push_back(
            segment(a.x(), a.y(), a.x() + len * std::cos(ang), a.y() + len * std::sin(ang), layer));
        break;
      }
      case 1: {  // on a cell boundary: integer x or y, integer ends
        const double c = static_cast<double>(random.integer(0, 20));
        const double lo = static_cast<double>(random.integer(0, 25));
        const double hi = lo + static_cast<double>(random.integer(1, 5));
        if (random.bernoulli(0.5))
          s.push_back(segment(c, lo * 0.8, c, hi * 0.8, layer));
        else
          s.push_back(segment(lo, c, hi, c, layer));
        break;
      }
      case 2: {  // a closed box: four segments sharing corners
        const double x = random.uniform(0, 28), y = random.uniform(0, 18);
        const double w = random.uniform(0.1, 2.0), h = random.uniform(0.1, 2.0);
        s.push_back(segment(x, y, x + w, y, layer));
        s.push_back(segment(x + w, y, x + w, y + h, layer));
        s.push_back(segment(x + w, y + h, x, y + h, layer));
        s.push_back(segment(x, y + h, x, y, layer));
        break;
      }
      case 3: {  // collinear overlapping pieces
        const Vector2d a(random.uniform(0, 25), random.uniform(0, 15));
        const Vector2d d = Vector2d(random.uniform(-1, 1), random.uniform(-1, 1)).normalized();
        s.push_back(segment(a.x(), a.y(), a.x() + 3 * d.x(), a.y() + 3 * d.y(), layer));
        s.push_back(
            segment(a.x() + d.x(), a.y() + d.y(), a.x() + 5 * d.x(), a.y() + 5 * d.y(), layer));
        break;
      }
      case 4:  // a duplicate of an earlier segment, on another layer
        if (!s.empty()) {
          Segment copy = s[static_cast<std::size_t>(random.integer(0, s.size() - 1))];
          copy.layer = layer;
          s.push_back(copy);
        }
        break;
      case 5: {  // zero length
        const double x = random.uniform(0, 30), y = random.uniform(0, 20);
        s.push_back(segment(x, y, x, y, layer));
        break;
      }
      default: {  // a long wall crossing many cells
        s.push_back(segment(random.uniform(-2, 32), random.uniform(-2, 22), random.uniform(-2, 32),
                            random.uniform(-2, 22), layer));
        break;
      }
    }
  }
  return s;
}

/// A ray: origin, unit direction, max range.
struct TestRay {
  Vector2d origin;
  Vector2d direction;
  double max_range;
};

/// Random rays of several kinds: anywhere (also outside the scene), from cell boundaries and
/// corners, exactly axis-parallel, aimed exactly at segment endpoints, starting on segments.
TestRay random_ray(Random& random, const std::vector<Segment>& scene) {
  TestRay ray;
  ray.max_range = random.bernoulli(0.2) ? random.uniform(0.1, 5.0) : random.uniform(5.0, 60.0);
  const double angle = random.uniform(-std::numbers::pi, std::numbers::pi);
  ray.direction = Vector2d(std::cos(angle), std::sin(angle));
  ray.origin = Vector2d(random.uniform(-10, 40), random.uniform(-10, 30));
  const Segment& s = scene[static_cast<std::size_t>(random.integer(0, scene.size() - 1))];
  switch (random.integer(0, 5)) {
    case 0:  // on a cell boundary (x or y integer) or a cell corner (both)
      ray.origin.x() = std::round(ray.origin.x());
      if (random.bernoulli(0.5))
        ray.origin.y() = std::round(ray.origin.y());
      break;
    case 1: {  // exactly axis-parallel
      const Vector2d axes[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      ray.direction = axes[random.integer(0, 3)];
      if (random.bernoulli(0.5))
        ray.origin = ray.origin.array().round();
      break;
    }
    case 2:  // aimed exactly at an endpoint (grazing it)
      if ((s.a - ray.origin).norm() > 0)
        ray.direction = (s.a - ray.origin).normalized();
      break;
    case 3:  // starting on a segment (or at its end), in any direction
      ray.origin = random.bernoulli(0.3) ? s.b : Vector2d(s.a + random.uniform() * (s.b - s.a));
      break;
    case 4:  // along a segment's direction from a point on its line
      if (s.length() > 0) {
        ray.direction = (s.b - s.a).normalized();
        ray.origin = s.a - random.uniform(0, 3) * ray.direction;
      }
      break;
    default:
      break;
  }
  return ray;
}

struct Mismatches {
  int count = 0;
  std::ostringstream first;
};

void compare(const SegmentRayCaster& caster, const TestRay& ray, Mismatches& m) {
  const auto fast = caster.cast_along(ray.origin, ray.direction, ray.max_range);
  const auto slow = brute_force(caster.segments(), ray.origin, ray.direction, ray.max_range);
  const bool same = fast.has_value() == slow.has_value() &&
                    (!fast || (fast->segment == slow->segment && fast->layer == slow->layer &&
                               std::abs(fast->range - slow->range) <= 1e-12));
  if (same)
    return;
  if (++m.count <= 5) {
    m.first.precision(17);
    m.first << "origin (" << ray.origin.transpose() << ") dir (" << ray.direction.transpose()
            << ") max " << ray.max_range << ": fast "
            << (fast ? std::to_string(fast->segment) + "@" + std::to_string(fast->range) : "none")
            << " slow "
            << (slow ? std::to_string(slow->segment) + "@" + std::to_string(slow->range) : "none")
            << "\n";
  }
}

TEST(SegmentRayCaster, MatchesBruteForceOnRandomScenes) {
  Random random(17);
  int hits = 0;
  // 100,000 rays for each cell size, over three scenes.
  for (int scene_index = 0; scene_index < 9; ++scene_index) {
    const double cell_size = std::array{1.0, 0.37, 4.0}[scene_index % 3];
    const std::vector<Segment> scene = random_scene(random, 400);
    const SegmentRayCaster caster(scene, {.cell_size = cell_size});
    // Cell boundaries lie at integer multiples of the cell size.
    EXPECT_NEAR(caster.grid_origin().x() / cell_size,
                std::round(caster.grid_origin().x() / cell_size), 1e-9);
    Mismatches m;
    for (int i = 0; i < 100'000 / 3; ++i) {
      const TestRay ray = random_ray(random, scene);
      compare(caster, ray, m);
      hits += caster.cast_along(ray.origin, ray.direction, ray.max_range).has_value() ? 1 : 0;
    }
    EXPECT_EQ(m.count, 0) << "cell size " << cell_size << "\n" << m.first.str();
  }
  EXPECT_GT(hits, 90'000);  // the comparison is not all misses
}

TEST(SegmentRayCaster, CastByAngleEqualsCastAlongTheSameDirection) {
  Random random(3);
  const std::vector<Segment> scene = random_scene(random, 200);
  const SegmentRayCaster caster(scene);
  Mismatches m;
  for (int i = 0; i < 20'000; ++i) {
    const Vector2d o(random.uniform(-5, 35), random.uniform(-5, 25));
    const double angle = random.uniform(-10, 10);
    const auto by_angle = caster.cast(o, angle, 40.0);
    const auto slow = brute_force(scene, o, {std::cos(angle), std::sin(angle)}, 40.0);
    ASSERT_EQ(by_angle.has_value(), slow.has_value());
    if (by_angle) {
      EXPECT_EQ(by_angle->segment, slow->segment);
      EXPECT_EQ(by_angle->range, slow->range);
    }
  }
}

TEST(SegmentRayCaster, SquareRoomFromItsCentreGivesAnalyticRanges) {
  // Room [-3, 3] x [-2, 2]: walls east 0, north 1, west 2, south 3 (layer = index + 10).
  const std::vector<Segment> room = {segment(3, -2, 3, 2, 10), segment(3, 2, -3, 2, 11),
                                     segment(-3, 2, -3, -2, 12), segment(-3, -2, 3, -2, 13)};
  const SegmentRayCaster caster(room);
  const double corner = std::atan2(2.0, 3.0);
  for (int i = 0; i < 3600; ++i) {
    const double angle = -std::numbers::pi + (i + 0.5) * (2 * std::numbers::pi / 3600);
    const double c = std::cos(angle), s = std::sin(angle);
    const double expected = std::min(3.0 / std::abs(c), 2.0 / std::abs(s));
    const auto hit = caster.cast({0, 0}, angle, 30.0);
    ASSERT_TRUE(hit) << angle;
    EXPECT_NEAR(hit->range, expected, 1e-12) << angle;
    int wall = 0;
    if (std::abs(angle) < corner)
      wall = 0;
    else if (angle > 0 && angle < std::numbers::pi - corner)
      wall = 1;
    else if (angle < 0 && angle > -std::numbers::pi + corner)
      wall = 3;
    else
      wall = 2;
    EXPECT_EQ(hit->segment, static_cast<std::size_t>(wall)) << angle;
    EXPECT_EQ(hit->layer, wall + 10) << angle;
  }
  // Max range cuts: the east wall is 3 m away straight ahead.
  EXPECT_TRUE(caster.cast_along({0, 0}, {1, 0}, 3.0));
  EXPECT_FALSE(caster.cast_along({0, 0}, {1, 0}, 2.999));
}

TEST(SegmentRayCaster, RaysThroughCornersAndEndpointsHit) {
  const std::vector<Segment> room = {segment(0, 0, 4, 0), segment(4, 0, 4, 4), segment(4, 4, 0, 4),
                                     segment(0, 4, 0, 0)};
  const SegmentRayCaster caster(room);
  // Exactly through each corner from the centre: no slipping through the crack.
  for (const Vector2d& corner : {Vector2d(0, 0), Vector2d(4, 0), Vector2d(4, 4), Vector2d(0, 4)}) {
    const Vector2d centre(2, 2);
    const auto hit = caster.cast_along(centre, (corner - centre).normalized(), 10.0);
    ASSERT_TRUE(hit) << corner.transpose();
    EXPECT_NEAR(hit->range, std::sqrt(8.0), 1e-12);
  }
  // From far inside, a sweep of 100k angles never escapes the closed room.
  Random random(8);
  for (int i = 0; i < 100'000; ++i) {
    const Vector2d o(random.uniform(0.001, 3.999), random.uniform(0.001, 3.999));
    ASSERT_TRUE(caster.cast(o, random.uniform(-4, 4), 10.0)) << i;
  }
  // A lone segment: grazing its endpoint hits, passing just beside it misses.
  const SegmentRayCaster lone({segment(2, -1, 2, 1)});
  const auto grazing = lone.cast_along({0, 0}, Vector2d(2, 1).normalized(), 10.0);
  ASSERT_TRUE(grazing);
  EXPECT_NEAR(grazing->range, std::sqrt(5.0), 1e-12);
  EXPECT_FALSE(lone.cast_along({0, 0}, Vector2d(2, 1.000001).normalized(), 10.0));
}

TEST(SegmentRayCaster, RaysStartingOnOrAlongASegmentDoNotHitIt) {
  // 0: the floor y = 0 the ray starts on; 1: a ceiling at y = 2; 2: a collinear piece ahead on
  // the floor's line; 3: a zero-length segment on the way up.
  const std::vector<Segment> scene = {segment(0, 0, 4, 0), segment(0, 2, 4, 2), segment(5, 0, 6, 0),
                                      segment(1, 1, 1, 1)};
  const SegmentRayCaster caster(scene);
  const auto up = caster.cast_along({1, 0}, {0, 1}, 10.0);
  ASSERT_TRUE(up);
  EXPECT_EQ(up->segment, 1u);  // not the floor at range 0, not the zero-length segment
  EXPECT_DOUBLE_EQ(up->range, 2.0);
  EXPECT_FALSE(caster.cast_along({1, 0}, {0, -1}, 10.0));  // leaves the floor downwards
  EXPECT_FALSE(caster.cast_along({1, 0}, {1, 0}, 10.0));   // edge-on along the floor line
  EXPECT_FALSE(caster.cast_along({-3, 0}, {1, 0}, 10.0));  // edge-on from before the floor
  // Parallel and offset: never hit.
  EXPECT_FALSE(caster.cast_along({-1, 1}, {1, 0}, 3.0));
  // From an endpoint of the ceiling, towards the floor: the floor at 2 m.
  const auto down = caster.cast_along({4, 2}, {0, -1}, 10.0);
  ASSERT_TRUE(down);
  EXPECT_EQ(down->segment, 0u);
}

TEST(SegmentRayCaster, DuplicateSegmentsGoToTheLowestIndex) {
  const std::vector<Segment> scene = {segment(5, -1, 5, 1, 7), segment(3, -1, 3, 1, 2),
                                      segment(3, -1, 3, 1, 1)};
  const SegmentRayCaster caster(scene);
  const auto hit = caster.cast_along({0, 0}, {1, 0}, 10.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->segment, 1u);
  EXPECT_EQ(hit->layer, 2);
}

TEST(SegmentRayCaster, FiftyThousandSegmentsStayExact) {
  // A warehouse-like field of 12,500 small boxes (50,000 segments) over 150 x 80 m.
  Random random(21);
  std::vector<Segment> scene;
  for (int i = 0; i < 12'500; ++i) {
    const double x = random.uniform(0, 150), y = random.uniform(0, 80);
    const double w = random.uniform(0.05, 0.6), h = random.uniform(0.05, 0.6);
    scene.push_back(segment(x, y, x + w, y, 0));
    scene.push_back(segment(x + w, y, x + w, y + h, 1));
    scene.push_back(segment(x + w, y + h, x, y + h, 2));
    scene.push_back(segment(x, y + h, x, y, 2));
  }
  const SegmentRayCaster caster(scene);
  EXPECT_EQ(caster.segments().size(), 50'000u);
  Mismatches m;
  for (int i = 0; i < 2'000; ++i)
    compare(caster, random_ray(random, scene), m);
  EXPECT_EQ(m.count, 0) << m.first.str();
  int hits = 0;
  for (int i = 0; i < 200'000; ++i)
    hits += caster.cast({random.uniform(0, 150), random.uniform(0, 80)}, random.uniform(-4, 4), 30)
                ? 1
                : 0;
  EXPECT_GT(hits, 190'000);  // dense clutter: nearly every ray hits within 30 m
}

TEST(SegmentRayCaster, MaxCellsGrowsTheCellSizeAndStaysExact) {
  Random random(5);
  std::vector<Segment> scene = random_scene(random, 300);
  scene.push_back(segment(-5000, -5000, -4999, -5000));  // a far outlier stretches the extent
  const SegmentRayCaster caster(scene, {.cell_size = 0.5, .max_cells = 10'000});
  EXPECT_GT(caster.cell_size(), 0.5);
  EXPECT_LE(static_cast<std::size_t>(caster.grid_width()) * caster.grid_height(), 10'000u);
  Mismatches m;
  for (int i = 0; i < 20'000; ++i)
    compare(caster, random_ray(random, scene), m);
  EXPECT_EQ(m.count, 0) << m.first.str();
}

TEST(SegmentRayCaster, EmptySceneAndDegenerateRaysGiveNothing) {
  const SegmentRayCaster empty({});
  EXPECT_FALSE(empty.cast({0, 0}, 0.3, 10));
  const SegmentRayCaster caster({segment(1, -1, 1, 1)});
  EXPECT_TRUE(caster.cast_along({0, 0}, {1, 0}, 10));
  EXPECT_FALSE(caster.cast_along({0, 0}, {0, 0}, 10));
  EXPECT_FALSE(caster.cast_along({0, 0}, {std::nan(""), 0}, 10));
  EXPECT_FALSE(caster.cast_along({std::numeric_limits<double>::infinity(), 0}, {1, 0}, 10));
  EXPECT_FALSE(caster.cast_along({0, 0}, {1, 0}, 0.0));
  EXPECT_TRUE(caster.cast_along({0, 0}, {1, 0}, std::numeric_limits<double>::infinity()));
}

TEST(SegmentRayCaster, BadInputNamesTheField) {
  test::expect_input_error([] { SegmentRayCaster({segment(0, 0, 1, 1)}, {.cell_size = 0.0}); },
                           {"ray_caster.cell_size"});
  test::expect_input_error(
      [] {
        SegmentRayCaster({segment(0, 0, 1, 1), segment(0, std::nan(""), 1, 1)});
      },
      {"segments", "segment 1"});
}

}  // namespace
}  // namespace floorgrid
