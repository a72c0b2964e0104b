#pragma once

// Exact arithmetic on floating-point expansions (Priest 1991; Shewchuk 1997, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates"). An expansion is a sum of
// doubles whose components do not overlap, stored from the smallest magnitude to the largest; its
// sign is the sign of its last (largest) component. The building blocks are the error-free
// transformations two_sum and two_product, exact for any finite inputs barring overflow, and
// barring underflow in two_product (the caller, predicates.cpp, scales its inputs to rule both
// out). Round-to-nearest-even IEEE double arithmetic is assumed.
//
// Contraction: the error-free transformations need every + and * rounded separately. GCC
// contracts a * b + c into an FMA by default for C++ when the target has one (-march=x86-64-v3),
// so this header switches contraction off for its own functions (push/pop keeps the setting local).
// two_product does not depend on it anyway: with a hardware FMA it calls std::fma explicitly, and
// without one (Dekker's splitting) the compiler has no FMA instruction to contract into.

#include <cmath>

#if defined(__FAST_MATH__)
#error "floorgrid's exact predicates need IEEE arithmetic: do not compile with -ffast-math"
#endif

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

namespace floorgrid::detail {

/// x = fl(a + b) and y = a + b - x exactly (Knuth's TwoSum, no precondition on magnitudes).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  const double b_roundoff = b - b_virtual;
  const double a_roundoff = a - a_virtual;
  y = a_roundoff + b_roundoff;
}

/// x = fl(a - b) and y = a - b - x exactly.
inline void two_diff(double a, double b, double& x, double& y) {
  two_sum(a, -b, x, y);
}

#if defined(__FP_FAST_FMA) || defined(FP_FAST_FMA) || defined(__FMA__)
inline constexpr bool kHardwareFma = true;
#else
inline constexpr bool kHardwareFma = false;
#endif

/// x = fl(a * b) and y = a * b - x exactly: with an explicit fused multiply-add where the target
/// has one, else by Dekker's splitting of each factor into two 26-bit halves.
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  if constexpr (kHardwareFma) {
    y = std::fma(a, b, -x);
  } else {
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1
    const double ca = kSplitter * a;
    const double a_hi = ca - (ca - a);
    const double a_lo = a - a_hi;
    const double cb = kSplitter * b;
    const double b_hi = cb - (cb - b);
    const double b_lo = b - b_hi;
    const double err1 = x - a_hi * b_hi;
    const double err2 = err1 - a_lo * b_hi;
    const double err3 = err2 - a_hi * b_lo;
    y = a_lo * b_lo - err3;
  }
}

/// h = e + b for an expansion e of `e_length` components; zero components are dropped. h has room
/// for e_length + 1 components and may not alias e. Returns the length of h (at least 1).
inline int grow_expansion(int e_length, const double* e, double b, double* h) {
  double q = b;
  int h_length = 0;
  for (int i = 0; i < e_length; ++i) {
    double sum = 0.0, tail = 0.0;
    two_sum(q, e[i], sum, tail);
    q = sum;
    if (tail != 0.0)
      h[h_length++] = tail;
  }
  if (q != 0.0 || h_length == 0)
    h[h_length++] = q;
  return h_length;
}

/// h = e + f; zero components are dropped. The components of both are merged by increasing
/// magnitude and accumulated with two_sum (Shewchuk's Theorem 13: the result is again a
/// nonoverlapping expansion). h has room for e_length + f_length components and may alias neither.
/// Returns the length of h (at least 1).
inline int expansion_sum(int e_length, const double* e, int f_length, const double* f, double* h) {
  int i = 0, j = 0, h_length = 0;
  auto next_smallest = [&]() {
    if (j >= f_length || (i < e_length && std::fabs(e[i]) <= std::fabs(f[j])))
      return e[i++];
    return f[j++];
  };
  if (e_length + f_length == 0) {
    h[0] = 0.0;
    return 1;
  }
  double q = next_smallest();
  while (i < e_length || j < f_length) {
    double sum = 0.0, tail = 0.0;
    two_sum(q, next_smallest(), sum, tail);
    q = sum;
    if (tail != 0.0)
      h[h_length++] = tail;
  }
  if (q != 0.0 || h_length == 0)
    h[h_length++] = q;
  return h_length;
}

/// h = b * e; zero components are dropped. h has room for 2 * e_length components and may not
/// alias e. Returns the length of h (at least 1).
inline int scale_expansion(int e_length, const double* e, double b, double* h) {
  int h_length = 0;
  double q = 0.0, tail = 0.0;
  two_product(e[0], b, q, tail);
  if (tail != 0.0)
    h[h_length++] = tail;
  for (int i = 1; i < e_length; ++i) {
    double product = 0.0, product_tail = 0.0, sum = 0.0;
    two_product(e[i], b, product, product_tail);
    two_sum(q, product_tail, sum, tail);
    if (tail != 0.0)
      h[h_length++] = tail;
    two_sum(product, sum, q, tail);  // |product| >= |sum|, but two_sum needs no ordering
    if (tail != 0.0)
      h[h_length++] = tail;
  }
  if (q != 0.0 || h_length == 0)
    h[h_length++] = q;
  return h_length;
}

/// An expansion of the exact product a * b - c * d (at most 4 components). Returns its length.
inline int two_two_diff_of_products(double a, double b, double c, double d, double* h) {
  double left[2], right[2];
  two_product(a, b, left[1], left[0]);
  two_product(c, d, right[1], right[0]);
  right[0] = -right[0];
  right[1] = -right[1];
  return expansion_sum(2, left, 2, right, h);
}

/// An approximation of an expansion's value whose sign is exact: the sum of its components from
/// the smallest, unless rounding made that sum lose the sign of the largest component (possible
/// when the smaller components nearly cancel it), in which case the largest component itself.
inline double expansion_value(int e_length, const double* e) {
  const double top = e[e_length - 1];
  double sum = 0.0;
  for (int i = 0; i < e_length; ++i)
    sum += e[i];
  if ((top > 0.0 && !(sum > 0.0)) || (top < 0.0 && !(sum < 0.0)) || top == 0.0)
    return top;
  return sum;
}

}  // namespace floorgrid::detail

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
