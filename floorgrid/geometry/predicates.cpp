#include "floorgrid/geometry/predicates.hpp"

// Switch off contraction of a * b + c into FMAs for the whole file, before any header's inline
// functions are seen: the filters' error bounds count one rounding per operation (an FMA would only
// remove roundings, but the bounds are proved for the code as written), and the error-free
// transformations in expansion_arithmetic.hpp need separate roundings (that header also protects
// itself). Clang contracts only within one expression and honours the standard pragma.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("fp-contract=off")
#endif
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>

#include "floorgrid/geometry/big_integer.hpp"
#include "floorgrid/geometry/expansion_arithmetic.hpp"

#if FLT_EVAL_METHOD != 0
#error "floorgrid's predicates need double arithmetic evaluated in double precision"
#endif

namespace floorgrid {
namespace {

using detail::BigInteger;

// Unit roundoff u = 2^-53 of round-to-nearest doubles.
constexpr double kU = 0x1.0p-53;

// Filter error bounds, as multiples of the permanent (the determinant with every term's absolute
// value). Counting roundings (each |delta| <= u) along the evaluation below gives, to first order,
// |error| <= 4u * permanent for orient2d and <= 11u * permanent for incircle, plus O(u^2) terms
// and the rounding of the computed permanent itself; 8u and 16u cover all of it with room to
// spare. (Shewchuk's sharper 3u and 10u would decide a few more calls in the filter; these are
// simpler to verify.)
constexpr double kOrientBound = 8.0 * kU;
constexpr double kIncircleBound = 16.0 * kU;

// The bounds above assume no underflow and no overflow. They are guaranteed when every coordinate
// difference is zero or within [low, high]: orient2d's products then lie in [2^-960, 2^960];
// incircle's degree-4 terms in [2^-1012, 2^963] (the one difference of products that may be small
// is either exact or at least 2^-532); both permanents, when nonzero, are at least 2^-960, so
// the bounds are normal numbers and bound * permanent is exact. Otherwise the exact path decides.
constexpr double kOrientLow = 0x1.0p-480;
constexpr double kOrientHigh = 0x1.0p+480;
constexpr double kIncircleLow = 0x1.0p-240;
constexpr double kIncircleHigh = 0x1.0p+240;

bool in_filter_range(double d, double low, double high) {
  const double m = std::fabs(d);
  return m <= high && (m >= low || m == 0.0);
}

// ---- the inputs of the exact paths ----

// Binary exponent of the lowest set bit of a finite nonzero x (x is a multiple of 2^result).
int lowest_bit_exponent(double x) {
  int exponent = 0;
  const double fraction = std::frexp(std::fabs(x), &exponent);
  const auto mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 53));
  return exponent - 53 + std::countr_zero(mantissa);
}

// How the exact paths treat a set of coordinates.
struct ExactScaling {
  bool finite = true;             // every coordinate finite
  bool all_zero = false;          // every coordinate zero: the determinant is 0
  bool expansions_exact = false;  // scaled by 2^shift, expansion arithmetic is exact
  int shift = 0;                  // power of two that brings the largest coordinate into [0.5, 1)
  int lowest_exponent = 0;        // smallest lowest_bit_exponent over the nonzero coordinates
};

// Expansion arithmetic is exact while every product is a multiple of 2^-1074 (two_product's
// error term is then representable) and nothing overflows. After scaling the largest coordinate
// into [0.5, 1), a degree-k polynomial is a sum of terms below 1 that are multiples of
// 2^(k * lowest exponent), so the condition is k * (lowest exponent + shift) >= -1074; a margin
// keeps clear of the subnormal edge.
template <std::size_t N>
ExactScaling exact_scaling(const std::array<double, N>& values, int degree) {
  ExactScaling s;
  double largest = 0.0;
  s.lowest_exponent = std::numeric_limits<int>::max();
  for (const double v : values) {
    if (!std::isfinite(v)) {
      s.finite = false;
      return s;
    }
    if (v != 0.0) {
      largest = std::max(largest, std::fabs(v));
      s.lowest_exponent = std::min(s.lowest_exponent, lowest_bit_exponent(v));
    }
  }
  if (largest == 0.0) {
    s.all_zero = true;
    return s;
  }
  s.shift = -(std::ilogb(largest) + 1);
  s.expansions_exact = degree * (s.lowest_exponent + s.shift) >= -1060;
  return s;
}

// value * 2^exponent without losing the sign: clamped to the smallest subnormal (or infinity).
double rescale(double value, int exponent) {
  if (value == 0.0)
    return 0.0;
  const double r = std::ldexp(value, exponent);
  if (r == 0.0)
    return std::copysign(std::numeric_limits<double>::denorm_min(), value);
  return r;
}

double from_big_integer(const BigInteger& value, int exponent) {
  int e = 0;
  const double m = value.approximate(e);
  return rescale(m, e + exponent);  // both within +-10^4: no int overflow
}

// ---- orient2d ----

double orient2d_filter(const double* a, const double* b, const double* c, bool& decided) {
  const double acx = a[0] - c[0];
  const double bcx = b[0] - c[0];
  const double acy = a[1] - c[1];
  const double bcy = b[1] - c[1];
  const double left = acx * bcy;
  const double right = acy * bcx;
  const double det = left - right;
  const double bound = kOrientBound * (std::fabs(left) + std::fabs(right));
  decided = std::fabs(det) > bound && in_filter_range(acx, kOrientLow, kOrientHigh) &&
            in_filter_range(bcx, kOrientLow, kOrientHigh) &&
            in_filter_range(acy, kOrientLow, kOrientHigh) &&
            in_filter_range(bcy, kOrientLow, kOrientHigh);
  return det;
}

double orient2d_big_integer_scaled(const std::array<double, 6>& v, int unit_exponent) {
  std::array<BigInteger, 6> x;
  for (std::size_t i = 0; i < 6; ++i)
    x[i] = BigInteger::from_double(v[i], unit_exponent);
  const BigInteger& ax = x[0];
  const BigInteger& ay = x[1];
  const BigInteger& bx = x[2];
  const BigInteger& by = x[3];
  const BigInteger& cx = x[4];
  const BigInteger& cy = x[5];
  const BigInteger det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
  return from_big_integer(det, 2 * unit_exponent);
}

double orient2d_exact_impl(const double* a, const double* b, const double* c, bool force_big) {
  const std::array<double, 6> raw = {a[0], a[1], b[0], b[1], c[0], c[1]};
  const ExactScaling s = exact_scaling(raw, 2);
  if (!s.finite)
    return std::numeric_limits<double>::quiet_NaN();
  if (s.all_zero)
    return 0.0;
  if (force_big || !s.expansions_exact)
    return orient2d_big_integer_scaled(raw, s.lowest_exponent);

  std::array<double, 6> v;
  for (std::size_t i = 0; i < 6; ++i)
    v[i] = std::ldexp(raw[i], s.shift);
  const double ax = v[0], ay = v[1], bx = v[2], by = v[3], cx = v[4], cy = v[5];

  double acx = 0, acx_tail = 0, bcx = 0, bcx_tail = 0, acy = 0, acy_tail = 0, bcy = 0, bcy_tail = 0;
  detail::two_diff(ax, cx, acx, acx_tail);
  detail::two_diff(bx, cx, bcx, bcx_tail);
  detail::two_diff(ay, cy, acy, acy_tail);
  detail::two_diff(by, cy, bcy, bcy_tail);
  double value = 0.0;
  if (acx_tail == 0.0 && bcx_tail == 0.0 && acy_tail == 0.0 && bcy_tail == 0.0) {
    // The differences are exact: the determinant of the translated points (4 components).
    double h[4];
    const int n = detail::two_two_diff_of_products(acx, bcy, acy, bcx, h);
    value = detail::expansion_value(n, h);
  } else {
    // ax*by - ax*cy - ay*bx + ay*cx + bx*cy - by*cx, every product exact (at most 12 components).
    double ab[4], bc[4], ca[4], abbc[8], sum[12];
    const int n_ab = detail::two_two_diff_of_products(ax, by, ay, bx, ab);
    const int n_bc = detail::two_two_diff_of_products(bx, cy, by, cx, bc);
    const int n_ca = detail::two_two_diff_of_products(cx, ay, cy, ax, ca);
    const int n_abbc = detail::expansion_sum(n_ab, ab, n_bc, bc, abbc);
    const int n = detail::expansion_sum(n_abbc, abbc, n_ca, ca, sum);
    value = detail::expansion_value(n, sum);
  }
  return rescale(value, -2 * s.shift);
}

// ---- incircle ----

double incircle_filter(const double* a, const double* b, const double* c, const double* d,
                       bool& decided) {
  const double adx = a[0] - d[0];
  const double bdx = b[0] - d[0];
  const double cdx = c[0] - d[0];
  const double ady = a[1] - d[1];
  const double bdy = b[1] - d[1];
  const double cdy = c[1] - d[1];

  const double bdxcdy = bdx * cdy;
  const double cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady;
  const double adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy;
  const double bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;

  const double det =
      alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double bound = kIncircleBound * permanent;
  decided = std::fabs(det) > bound && in_filter_range(adx, kIncircleLow, kIncircleHigh) &&
            in_filter_range(bdx, kIncircleLow, kIncircleHigh) &&
            in_filter_range(cdx, kIncircleLow, kIncircleHigh) &&
            in_filter_range(ady, kIncircleLow, kIncircleHigh) &&
            in_filter_range(bdy, kIncircleLow, kIncircleHigh) &&
            in_filter_range(cdy, kIncircleLow, kIncircleHigh);
  return det;
}

double incircle_big_integer_scaled(const std::array<double, 8>& v, int unit_exponent) {
  std::array<BigInteger, 8> x;
  for (std::size_t i = 0; i < 8; ++i)
    x[i] = BigInteger::from_double(v[i], unit_exponent);
  const BigInteger adx = x[0] - x[6];
  const BigInteger ady = x[1] - x[7];
  const BigInteger bdx = x[2] - x[6];
  const BigInteger bdy = x[3] - x[7];
  const BigInteger cdx = x[4] - x[6];
  const BigInteger cdy = x[5] - x[7];
  const BigInteger alift = adx * adx + ady * ady;
  const BigInteger blift = bdx * bdx + bdy * bdy;
  const BigInteger clift = cdx * cdx + cdy * cdy;
  const BigInteger det = alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) +
                         clift * (adx * bdy - bdx * ady);
  return from_big_integer(det, 4 * unit_exponent);
}

// lift * m for an expansion m and a lift x^2 + y^2 of doubles: x*(x*m) + y*(y*m), exact.
// `out` needs room for 8 * m_length components.
int lift_times(double x, double y, int m_length, const double* m, double* out) {
  double xm[64], xxm[128], ym[64], yym[128];
  const int n_xm = detail::scale_expansion(m_length, m, x, xm);
  const int n_xxm = detail::scale_expansion(n_xm, xm, x, xxm);
  const int n_ym = detail::scale_expansion(m_length, m, y, ym);
  const int n_yym = detail::scale_expansion(n_ym, ym, y, yym);
  return detail::expansion_sum(n_xxm, xxm, n_yym, yym, out);
}

// orient2d(p, q, r) of raw (scaled) coordinates as an expansion of at most 12 components.
int orient_expansion(const double* p, const double* q, const double* r, double* out) {
  double pq[4], qr[4], rp[4], pqqr[8];
  const int n_pq = detail::two_two_diff_of_products(p[0], q[1], p[1], q[0], pq);
  const int n_qr = detail::two_two_diff_of_products(q[0], r[1], q[1], r[0], qr);
  const int n_rp = detail::two_two_diff_of_products(r[0], p[1], r[1], p[0], rp);
  const int n_pqqr = detail::expansion_sum(n_pq, pq, n_qr, qr, pqqr);
  return detail::expansion_sum(n_pqqr, pqqr, n_rp, rp, out);
}

double incircle_exact_impl(const double* a, const double* b, const double* c, const double* d,
                           bool force_big) {
  const std::array<double, 8> raw = {a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]};
  const ExactScaling s = exact_scaling(raw, 4);
  if (!s.finite)
    return std::numeric_limits<double>::quiet_NaN();
  if (s.all_zero)
    return 0.0;
  if (force_big || !s.expansions_exact)
    return incircle_big_integer_scaled(raw, s.lowest_exponent);

  std::array<double, 8> v;
  for (std::size_t i = 0; i < 8; ++i)
    v[i] = std::ldexp(raw[i], s.shift);
  const double* pa = &v[0];
  const double* pb = &v[2];
  const double* pc = &v[4];
  const double* pd = &v[6];

  std::array<double, 6> diff, tail;
  detail::two_diff(pa[0], pd[0], diff[0], tail[0]);
  detail::two_diff(pa[1], pd[1], diff[1], tail[1]);
  detail::two_diff(pb[0], pd[0], diff[2], tail[2]);
  detail::two_diff(pb[1], pd[1], diff[3], tail[3]);
  detail::two_diff(pc[0], pd[0], diff[4], tail[4]);
  detail::two_diff(pc[1], pd[1], diff[5], tail[5]);
  const bool differences_exact =
      std::all_of(tail.begin(), tail.end(), [](double t) { return t == 0.0; });

  double value = 0.0;
  if (differences_exact) {
    // The determinant of the translated points: alift*(bdx*cdy - cdx*bdy) + ... with exact
    // differences (each minor 4 components, each lifted term 32, the sum at most 96).
    const double adx = diff[0], ady = diff[1], bdx = diff[2], bdy = diff[3], cdx = diff[4],
                 cdy = diff[5];
    double bc[4], ca[4], ab[4];
    const int n_bc = detail::two_two_diff_of_products(bdx, cdy, cdx, bdy, bc);
    const int n_ca = detail::two_two_diff_of_products(cdx, ady, adx, cdy, ca);
    const int n_ab = detail::two_two_diff_of_products(adx, bdy, bdx, ady, ab);
    double at[32], bt[32], ct[32], abt[64], sum[96];
    const int n_at = lift_times(adx, ady, n_bc, bc, at);
    const int n_bt = lift_times(bdx, bdy, n_ca, ca, bt);
    const int n_ct = lift_times(cdx, cdy, n_ab, ab, ct);
    const int n_abt = detail::expansion_sum(n_at, at, n_bt, bt, abt);
    const int n = detail::expansion_sum(n_abt, abt, n_ct, ct, sum);
    value = detail::expansion_value(n, sum);
  } else {
    // The 4x4 lifted determinant expanded along the lift column, on raw coordinates:
    // alift*O(b,c,d) - blift*O(a,c,d) + clift*O(a,b,d) - dlift*O(a,b,c), every product exact.
    double o[12], terms[4][96];
    int n_terms[4];
    const double* const points[4] = {pa, pb, pc, pd};
    for (int k = 0; k < 4; ++k) {
      const double* others[3];
      for (int i = 0, j = 0; i < 4; ++i) {
        if (i != k)
          others[j++] = points[i];
      }
      int n_o = orient_expansion(others[0], others[1], others[2], o);
      if (k % 2 == 1) {
        for (int i = 0; i < n_o; ++i)
          o[i] = -o[i];
      }
      n_terms[k] = lift_times(points[k][0], points[k][1], n_o, o, terms[k]);
    }
    double first[192], second[192], sum[384];
    const int n_first = detail::expansion_sum(n_terms[0], terms[0], n_terms[1], terms[1], first);
    const int n_second = detail::expansion_sum(n_terms[2], terms[2], n_terms[3], terms[3], second);
    const int n = detail::expansion_sum(n_first, first, n_second, second, sum);
    value = detail::expansion_value(n, sum);
  }
  return rescale(value, -4 * s.shift);
}

}  // namespace

double orient2d(const double* a, const double* b, const double* c) {
  bool decided = false;
  const double det = orient2d_filter(a, b, c, decided);
  if (decided)
    return det;
  return orient2d_exact_impl(a, b, c, false);
}

double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return orient2d(a.data(), b.data(), c.data());
}

double incircle(const double* a, const double* b, const double* c, const double* d) {
  bool decided = false;
  const double det = incircle_filter(a, b, c, d, decided);
  if (decided)
    return det;
  return incircle_exact_impl(a, b, c, d, false);
}

double incircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                const Eigen::Vector2d& d) {
  return incircle(a.data(), b.data(), c.data(), d.data());
}

namespace detail {

double orient2d_exact(const double* a, const double* b, const double* c) {
  return orient2d_exact_impl(a, b, c, false);
}

double incircle_exact(const double* a, const double* b, const double* c, const double* d) {
  return incircle_exact_impl(a, b, c, d, false);
}

double orient2d_big_integer(const double* a, const double* b, const double* c) {
  return orient2d_exact_impl(a, b, c, true);
}

double incircle_big_integer(const double* a, const double* b, const double* c, const double* d) {
  return incircle_exact_impl(a, b, c, d, true);
}

}  // namespace detail
}  // namespace floorgrid
