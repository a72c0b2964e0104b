#include "floorgrid/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

__extension__ typedef __int128 Int128;

int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}

// ---- exact references, independent of the library's arithmetic ----

// Binary exponent of the lowest set bit of a nonzero double.
int lowest_bit(double x) {
  int e = 0;
  const double f = std::frexp(std::fabs(x), &e);
  auto m = static_cast<std::uint64_t>(std::ldexp(f, 53));
  int shift = 0;
  while ((m & 1u) == 0u) {
    m >>= 1;
    ++shift;
  }
  return e - 53 + shift;
}

// The smallest exponent s such that every value is an integer multiple of 2^s.
int common_unit(const std::vector<double>& values) {
  int unit = 0;
  bool any = false;
  for (const double v : values) {
    if (v != 0.0) {
      unit = any ? std::min(unit, lowest_bit(v)) : lowest_bit(v);
      any = true;
    }
  }
  return unit;
}

// x / 2^unit as an integer; the test fails if it does not fit in 62 bits.
std::int64_t to_integer(double x, int unit) {
  const double scaled = std::ldexp(x, -unit);
  EXPECT_LT(std::fabs(scaled), 0x1.0p62) << "reference out of range";
  return static_cast<std::int64_t>(scaled);
}

// orient2d sign with __int128 on integer-scaled inputs (differences < 2^62: products < 2^125).
int reference_orient(const std::array<double, 2>& a, const std::array<double, 2>& b,
                     const std::array<double, 2>& c) {
  const int unit = common_unit({a[0], a[1], b[0], b[1], c[0], c[1]});
  const Int128 ax = to_integer(a[0], unit), ay = to_integer(a[1], unit);
  const Int128 bx = to_integer(b[0], unit), by = to_integer(b[1], unit);
  const Int128 cx = to_integer(c[0], unit), cy = to_integer(c[1], unit);
  const Int128 det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
  return (det > 0) - (det < 0);
}

// A signed integer as base-2^24 digits (least significant first), written for the tests only:
// after normalize() every digit but the top one lies in [0, 2^24) and the top one carries the sign.
struct Wide {
  std::vector<std::int64_t> digits;

  static Wide of(std::int64_t v) {
    Wide w;
    w.digits = {v};
    w.normalize();
    return w;
  }
  void normalize() {
    std::int64_t carry = 0;
    for (auto& d : digits) {
      d += carry;
      const std::int64_t low = ((d % (1 << 24)) + (1 << 24)) % (1 << 24);
      carry = (d - low) / (1 << 24);
      d = low;
    }
    while (carry != 0 && carry != -1) {
      const std::int64_t low = ((carry % (1 << 24)) + (1 << 24)) % (1 << 24);
      digits.push_back(low);
      carry = (carry - low) / (1 << 24);
    }
    if (carry == -1)
      digits.push_back(-1);
  }
  int sign() const {
    if (!digits.empty() && digits.back() < 0)
      return -1;
    for (const auto d : digits) {
      if (d != 0)
        return 1;
    }
    return 0;
  }
};

Wide operator+(const Wide& a, const Wide& b) {
  // The value is linear in the digits (a top digit of -1 stands for -B^k), so digits add.
  Wide r;
  r.digits.assign(std::max(a.digits.size(), b.digits.size()), 0);
  for (std::size_t i = 0; i < r.digits.size(); ++i)
    r.digits[i] = (i < a.digits.size() ? a.digits[i] : 0) + (i < b.digits.size() ? b.digits[i] : 0);
  r.normalize();
  return r;
}

Wide negate(const Wide& a) {
  Wide r = a;
  for (auto& d : r.digits)
    d = -d;
  r.normalize();
  return r;
}

Wide operator-(const Wide& a, const Wide& b) {
  return a + negate(b);
}

Wide operator*(const Wide& a, const Wide& b) {
  Wide r;
  r.digits.assign(a.digits.size() + b.digits.size() + 1, 0);
  for (std::size_t i = 0; i < a.digits.size(); ++i) {
    for (std::size_t j = 0; j < b.digits.size(); ++j)
      r.digits[i + j] += a.digits[i] * b.digits[j];
  }
  r.normalize();
  return r;
}

// incircle sign with Wide integers on integer-scaled inputs.
int reference_incircle(const std::array<double, 2>& a, const std::array<double, 2>& b,
                       const std::array<double, 2>& c, const std::array<double, 2>& d) {
  const int unit = common_unit({a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]});
  auto w = [unit](double v) { return Wide::of(to_integer(v, unit)); };
  const Wide adx = w(a[0]) - w(d[0]), ady = w(a[1]) - w(d[1]);
  const Wide bdx = w(b[0]) - w(d[0]), bdy = w(b[1]) - w(d[1]);
  const Wide cdx = w(c[0]) - w(d[0]), cdy = w(c[1]) - w(d[1]);
  const Wide det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                   (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                   (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
  return det.sign();
}

using P = std::array<double, 2>;

int orient_sign(const P& a, const P& b, const P& c) {
  return sign_of(orient2d(a.data(), b.data(), c.data()));
}
int incircle_sign(const P& a, const P& b, const P& c, const P& d) {
  return sign_of(incircle(a.data(), b.data(), c.data(), d.data()));
}

TEST(PredicatesReference, WideIntegersAgreeWithInt128) {
  Random random(3);
  for (int i = 0; i < 2000; ++i) {
    const std::int64_t x = random.integer(-(std::int64_t{1} << 40), std::int64_t{1} << 40);
    const std::int64_t y = random.integer(-(std::int64_t{1} << 40), std::int64_t{1} << 40);
    const std::int64_t z = random.integer(-(std::int64_t{1} << 40), std::int64_t{1} << 40);
    const Int128 exact = Int128{x} * y - Int128{z} * z + x;
    const Wide wide = Wide::of(x) * Wide::of(y) - Wide::of(z) * Wide::of(z) + Wide::of(x);
    ASSERT_EQ(wide.sign(), (exact > 0) - (exact < 0)) << x << " " << y << " " << z;
  }
}

// ---- orient2d ----

TEST(PredicatesOrient, SignsOfSimpleTriangles) {
  const Eigen::Vector2d a(0, 0), b(1, 0), c(0, 1), d(2, 0);
  EXPECT_GT(orient2d(a, b, c), 0.0);
  EXPECT_LT(orient2d(a, c, b), 0.0);
  EXPECT_EQ(orient2d(a, b, d), 0.0);
  EXPECT_DOUBLE_EQ(orient2d(a, b, c), 1.0);  // twice the area
}

// The classic failure of naive orientation (Kettner et al., "Classroom examples of robustness
// problems"): a point near (0.5, 0.5) moved by single ulps against the line through (12, 12) and
// (24, 24), the diagonal y = x. The naive formula gives a scrambled sign pattern; the exact one
// must be the true one: positive above the diagonal, negative below, zero on it.
TEST(PredicatesOrient, UlpGridAroundTheDiagonalMatchesExactReference) {
  const P b = {12.0, 12.0};
  const P c = {24.0, 24.0};
  int naive_wrong = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      const P a = {0.5 + i * 0x1.0p-53, 0.5 + j * 0x1.0p-53};
      const int expected = reference_orient(a, b, c);
      ASSERT_EQ(expected, (i < j) - (i > j));  // a above the diagonal (y > x): left of b -> c
      ASSERT_EQ(orient_sign(a, b, c), expected) << i << " " << j;
      ASSERT_EQ(orient_sign(b, c, a), expected);
      ASSERT_EQ(orient_sign(c, b, a), -expected);
      const double naive = (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
      naive_wrong += sign_of(naive) != expected;
    }
  }
  EXPECT_GT(naive_wrong, 1000) << "the grid should defeat plain floating point";
}

TEST(PredicatesOrient, UlpGridOnOtherLinesMatchesExactReference) {
  // Lines whose points are not exactly representable: b and c are rounded, the reference uses the
  // doubles as they are.
  const std::vector<std::array<P, 2>> lines = {
      {{{17.300000000000001, 17.300000000000001}, {24.00000000000005, 24.0000000000000053}}},
      {{{0.1, 0.3}, {1.7, 5.1}}},
      {{{-3.25, 7.0}, {11.125, -2.0}}},
  };
  for (const auto& line : lines) {
    for (int i = -40; i < 40; ++i) {
      for (int j = -40; j < 40; ++j) {
        P a = {0.5, 0.5};
        // a on (or next to) the line at parameter 0.5 between the two points, then ulp steps.
        a[0] = 0.5 * (line[0][0] + line[1][0]);
        a[1] = 0.5 * (line[0][1] + line[1][1]);
        for (int k = 0; k < std::abs(i); ++k)
          a[0] = std::nextafter(a[0], i > 0 ? INFINITY : -INFINITY);
        for (int k = 0; k < std::abs(j); ++k)
          a[1] = std::nextafter(a[1], j > 0 ? INFINITY : -INFINITY);
        const int expected = reference_orient(a, line[0], line[1]);
        ASSERT_EQ(orient_sign(a, line[0], line[1]), expected);
        ASSERT_EQ(orient_sign(line[1], a, line[0]), expected);
      }
    }
  }
}

TEST(PredicatesOrient, HugeAndTinyMagnitudes) {
  // Scaling every coordinate by a power of two scales the determinant by its square: the sign of
  // the ulp grid above must survive scales from 2^-1000 to 2^+1000 (the filter cannot decide
  // there: its products would under- or overflow).
  for (const int scale : {-1000, -600, -300, 300, 600, 1000}) {
    const P b = {std::ldexp(12.0, scale), std::ldexp(12.0, scale)};
    const P c = {std::ldexp(24.0, scale), std::ldexp(24.0, scale)};
    for (int i = 0; i < 16; ++i) {
      for (int j = 0; j < 16; ++j) {
        const P a = {std::ldexp(0.5 + i * 0x1.0p-53, scale),
                     std::ldexp(0.5 + j * 0x1.0p-53, scale)};
        ASSERT_EQ(orient_sign(a, b, c), (i < j) - (i > j)) << scale << " " << i << " " << j;
      }
    }
  }
  // Subnormal coordinates: the determinant underflows, but its sign and nonzero-ness must not.
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_GT(orient2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(tiny, 0), Eigen::Vector2d(0, tiny)),
            0.0);
  EXPECT_EQ(orient2d(Eigen::Vector2d(tiny, tiny), Eigen::Vector2d(2 * tiny, 2 * tiny),
                     Eigen::Vector2d(5 * tiny, 5 * tiny)),
            0.0);
  // Mixed magnitudes spanning 2^2000: only the big-integer path is exact here.
  // det = bx*cy - by*cx = 2^1000 * (cy - cx) with cy - cx = 2^-1050 > 0.
  const Eigen::Vector2d o(0, 0);
  const Eigen::Vector2d far(std::ldexp(1.0, 1000), std::ldexp(1.0, 1000));
  const Eigen::Vector2d near(std::ldexp(1.0, -1000),
                             std::ldexp(1.0, -1000) + std::ldexp(1.0, -1050));
  EXPECT_GT(orient2d(o, far, near), 0.0);
  EXPECT_LT(orient2d(o, near, far), 0.0);
  const Eigen::Vector2d on(std::ldexp(1.0, -1000), std::ldexp(1.0, -1000));
  EXPECT_EQ(orient2d(o, far, on), 0.0);
  // Huge coordinates whose differences overflow: (-M, -M), (M, M) and a point beside the line.
  const double m = std::numeric_limits<double>::max();
  EXPECT_GT(orient2d(Eigen::Vector2d(-m, -m), Eigen::Vector2d(m, m), Eigen::Vector2d(0, 1e-300)),
            0.0);
  EXPECT_EQ(orient2d(Eigen::Vector2d(-m, -m), Eigen::Vector2d(m, m), Eigen::Vector2d(1, 1)), 0.0);
}

TEST(PredicatesOrient, NonFiniteGivesNaN) {
  const Eigen::Vector2d a(0, 0), b(1, 0);
  EXPECT_TRUE(std::isnan(orient2d(a, b, Eigen::Vector2d(NAN, 1))));
  EXPECT_TRUE(std::isnan(orient2d(a, b, Eigen::Vector2d(INFINITY, 1))));
}

// ---- incircle ----

TEST(PredicatesIncircle, SignsOfSimpleCircles) {
  const Eigen::Vector2d a(0, 0), b(1, 0), c(0, 1);
  EXPECT_GT(incircle(a, b, c, Eigen::Vector2d(0.5, 0.5)), 0.0);
  EXPECT_LT(incircle(a, b, c, Eigen::Vector2d(2, 2)), 0.0);
  EXPECT_EQ(incircle(a, b, c, Eigen::Vector2d(1, 1)), 0.0);      // the square's fourth corner
  EXPECT_LT(incircle(a, c, b, Eigen::Vector2d(0.5, 0.5)), 0.0);  // clockwise flips the sign
}

// Integer points on the circle x^2 + y^2 = 5^20 (from powers of 3 + 4i): large enough that the
// floating-point filter cannot decide, exactly co-circular, and translated far from the origin.
std::vector<P> cocircular_points(double offset_x, double offset_y) {
  std::vector<P> points;
  for (int k = 0; k <= 10; ++k) {
    // (3 + 4i)^k (3 - 4i)^(10 - k)
    std::int64_t re = 1, im = 0;
    for (int i = 0; i < 10; ++i) {
      const std::int64_t b = i < k ? 4 : -4;
      const std::int64_t r = re * 3 - im * b;
      im = re * b + im * 3;
      re = r;
    }
    points.push_back({static_cast<double>(re) + offset_x, static_cast<double>(im) + offset_y});
    points.push_back({-static_cast<double>(im) + offset_x, static_cast<double>(re) + offset_y});
  }
  return points;
}

TEST(PredicatesIncircle, CocircularIntegerPointsGiveZero) {
  for (const auto& [ox, oy] : std::vector<std::pair<double, double>>{{0, 0}, {1e6, -3e5}}) {
    const std::vector<P> pts = cocircular_points(ox, oy);
    int checked = 0;
    for (std::size_t i = 0; i + 3 < pts.size(); i += 3) {
      const P& a = pts[i];
      const P& b = pts[i + 1];
      const P& c = pts[i + 2];
      const P& d = pts[i + 3];
      ASSERT_EQ(reference_incircle(a, b, c, d), 0);
      EXPECT_EQ(incircle_sign(a, b, c, d), 0) << i;
      // One unit (exact in doubles) inward or outward along x decides it.
      const P inward = {d[0] - (d[0] - ox > 0 ? 1.0 : -1.0), d[1]};
      const int expected = reference_incircle(a, b, c, inward);
      EXPECT_EQ(incircle_sign(a, b, c, inward), expected);
      ++checked;
    }
    EXPECT_GE(checked, 5);
  }
}

TEST(PredicatesIncircle, UlpGridAroundACircleMatchesExactReference) {
  // a, b, c on the circle of radius 5 about the origin; d = (4, -3) on it too, moved by ulps.
  const P a = {5.0, 0.0}, b = {3.0, 4.0}, c = {-4.0, 3.0};
  int naive_wrong = 0;
  for (int i = -24; i <= 24; ++i) {
    for (int j = -24; j <= 24; ++j) {
      P d = {4.0, -3.0};
      for (int k = 0; k < std::abs(i); ++k)
        d[0] = std::nextafter(d[0], i > 0 ? INFINITY : -INFINITY);
      for (int k = 0; k < std::abs(j); ++k)
        d[1] = std::nextafter(d[1], j > 0 ? INFINITY : -INFINITY);
      const int expected = reference_incircle(a, b, c, d);
      ASSERT_EQ(incircle_sign(a, b, c, d), expected) << i << " " << j;
      ASSERT_EQ(incircle_sign(b, a, c, d), -expected);
      ASSERT_EQ(incircle_sign(b, c, a, d), expected);
      // The 4x4 lifted determinant is antisymmetric in all four points.
      ASSERT_EQ(incircle_sign(d, b, c, a), -expected);
      const double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1],
                   cdx = c[0] - d[0], cdy = c[1] - d[1];
      const double naive = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                           (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
      naive_wrong += sign_of(naive) != expected;
    }
  }
  EXPECT_GT(naive_wrong, 0) << "the grid should defeat plain floating point";
}

TEST(PredicatesIncircle, HugeAndTinyMagnitudes) {
  // The degree-4 determinant scales by 2^(4 scale): filter products under/overflow beyond 2^+-250.
  const P a0 = {5.0, 0.0}, b0 = {3.0, 4.0}, c0 = {-4.0, 3.0};
  for (const int scale : {-1000, -500, -260, 260, 500, 1000}) {
    auto s = [scale](const P& p) { return P{std::ldexp(p[0], scale), std::ldexp(p[1], scale)}; };
    for (int i = -3; i <= 3; ++i) {
      for (int j = -3; j <= 3; ++j) {
        P d = {4.0, -3.0};
        for (int k = 0; k < std::abs(i); ++k)
          d[0] = std::nextafter(d[0], i > 0 ? INFINITY : -INFINITY);
        for (int k = 0; k < std::abs(j); ++k)
          d[1] = std::nextafter(d[1], j > 0 ? INFINITY : -INFINITY);
        ASSERT_EQ(incircle_sign(s(a0), s(b0), s(c0), s(d)), reference_incircle(a0, b0, c0, d))
            << scale << " " << i << " " << j;
      }
    }
  }
  // Mixed magnitudes (big-integer path): a tiny triangle near the origin and a far point outside,
  // a point just inside it, and one exactly on its circle.
  const double t = std::ldexp(1.0, -900);
  const Eigen::Vector2d a(0, 0), b(t, 0), c(0, t);
  EXPECT_LT(incircle(a, b, c, Eigen::Vector2d(std::ldexp(1.0, 900), 0)), 0.0);
  EXPECT_GT(incircle(a, b, c, Eigen::Vector2d(std::nextafter(t, 0.0), t)), 0.0);
  EXPECT_EQ(incircle(a, b, c, Eigen::Vector2d(t, t)), 0.0);
  // A circle of radius 2^900 about the origin: (2^-900, -R) lies outside by 2^-1800 in squared
  // distance, (0, -R) on it.
  const double big = std::ldexp(1.0, 900);
  const Eigen::Vector2d west(-big, 0), east(big, 0), north(0, big);
  EXPECT_LT(incircle(west, east, north, Eigen::Vector2d(t, -big)), 0.0);
  EXPECT_EQ(incircle(west, east, north, Eigen::Vector2d(0, -big)), 0.0);
  EXPECT_GT(incircle(west, east, north, Eigen::Vector2d(t, std::nextafter(-big, 0.0))), 0.0);
  const double m = std::numeric_limits<double>::max() / 4;
  EXPECT_GT(incircle(Eigen::Vector2d(-m, 0), Eigen::Vector2d(m, 0), Eigen::Vector2d(0, m),
                     Eigen::Vector2d(1e-300, -1e-300)),
            0.0);
}

TEST(PredicatesIncircle, NonFiniteGivesNaN) {
  const Eigen::Vector2d a(0, 0), b(1, 0), c(0, 1);
  EXPECT_TRUE(std::isnan(incircle(a, b, c, Eigen::Vector2d(NAN, 0))));
  EXPECT_TRUE(std::isnan(incircle(a, b, Eigen::Vector2d(-INFINITY, 0), c)));
}

// ---- the three arithmetic paths agree ----

TEST(PredicatesPaths, FilterExpansionsAndBigIntegersAgree) {
  // Nearly degenerate random configurations with random binary scales (-300..300) and offsets:
  // points on a line or circle, rounded, then moved by a few ulps.
  Random random(11);
  int zeros = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int scale = static_cast<int>(random.integer(-300, 300));
    // Every other trial is exactly degenerate: integer multiples of 2^scale, no jitter.
    const bool exact = trial % 2 == 0;
    auto coordinate = [&](double range) {
      return exact ? std::ldexp(static_cast<double>(random.integer(-1000, 1000)), scale)
                   : std::ldexp(random.uniform(-range, range), scale);
    };
    const double ox = coordinate(4);
    const double oy = coordinate(4);
    auto jitter = [&](double v) {
      if (exact)
        return v;
      const int steps = static_cast<int>(random.integer(-2, 2));
      for (int k = 0; k < std::abs(steps); ++k)
        v = std::nextafter(v, steps > 0 ? INFINITY : -INFINITY);
      return v;
    };
    const double dx = coordinate(1);
    const double dy = coordinate(1);
    std::array<P, 4> p;
    for (int k = 0; k < 3; ++k) {
      const double s = exact ? static_cast<double>(random.integer(-4, 4)) : random.uniform(-2, 2);
      p[static_cast<std::size_t>(k)] = {jitter(ox + s * dx), jitter(oy + s * dy)};
    }
    const double r = std::ldexp(random.uniform(0.5, 1), scale);
    const double angle = random.uniform(0, 6.283185307179586);
    p[3] = {jitter(p[0][0] + r * std::cos(angle)), jitter(p[0][1] + r * std::sin(angle))};

    const int o = sign_of(orient2d(p[0].data(), p[1].data(), p[2].data()));
    ASSERT_EQ(o, sign_of(detail::orient2d_exact(p[0].data(), p[1].data(), p[2].data())));
    ASSERT_EQ(o, sign_of(detail::orient2d_big_integer(p[0].data(), p[1].data(), p[2].data())));
    zeros += o == 0;
    // A circle through three of a right-angled triangle's corners and the fourth corner.
    const P q0 = p[0];
    const P q1 = {jitter(p[0][0] + dx), p[0][1]};
    const P q2 = {p[0][0], jitter(p[0][1] + dy)};
    const P q3 = {jitter(q1[0]), jitter(q2[1])};
    const int c = sign_of(incircle(q0.data(), q1.data(), q2.data(), q3.data()));
    ASSERT_EQ(c, sign_of(detail::incircle_exact(q0.data(), q1.data(), q2.data(), q3.data())));
    ASSERT_EQ(c, sign_of(detail::incircle_big_integer(q0.data(), q1.data(), q2.data(), q3.data())));
    const int c2 = sign_of(incircle(p[0].data(), p[1].data(), p[3].data(), p[2].data()));
    ASSERT_EQ(c2, sign_of(detail::incircle_big_integer(p[0].data(), p[1].data(), p[3].data(),
                                                       p[2].data())));
  }
  EXPECT_GT(zeros, 1000);
}

TEST(PredicatesPaths, ExactValuesAreAccurate) {
  // The exact paths return the determinant rounded (approximately): compare with a case whose
  // value is known.
  const double a[2] = {1e8 + 1, 1e8}, b[2] = {1e8, 1e8 + 1}, c[2] = {1e8, 1e8};
  EXPECT_DOUBLE_EQ(detail::orient2d_exact(a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(detail::orient2d_big_integer(a, b, c), 1.0);
  const double d[2] = {1e8 + 1, 1e8 + 1};
  EXPECT_DOUBLE_EQ(detail::incircle_exact(a, b, c, d), 0.0);
  const double e[2] = {1e8 + 0.5, 1e8 + 0.5};  // the centre: inside by r^2 * orient = 0.5
  EXPECT_GT(detail::incircle_exact(a, b, c, e), 0.0);
  EXPECT_GT(detail::incircle_big_integer(a, b, c, e), 0.0);
}

}  // namespace
}  // namespace floorgrid
