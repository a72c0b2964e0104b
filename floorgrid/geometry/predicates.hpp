#pragma once

#include <Eigen/Core>

namespace floorgrid {

/// Twice the signed area of the triangle (a, b, c): positive when a, b, c turn counter-clockwise,
/// negative when clockwise, zero when collinear. The sign is exact for all finite inputs: a
/// floating-point evaluation with a rigorous error bound decides nearly every call, and only when
/// it cannot, exact arithmetic on floating-point expansions (Shewchuk 1997) does, or a big
/// integer when the finest bit of some coordinate lies more than 530 binary orders of magnitude
/// below the largest coordinate (where products of expansions would underflow). The magnitude
/// approximates the determinant (a nonzero determinant never gives 0; a huge one may give
/// +-infinity). A NaN or infinite coordinate gives NaN.
double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// orient2d on raw (x, y) pairs: a, b and c each point to two doubles.
double orient2d(const double* a, const double* b, const double* c);

/// Positive when d lies strictly inside the circle through a, b, c (which must turn
/// counter-clockwise; the sign flips when they turn clockwise), negative when strictly outside,
/// zero when the four points are co-circular (or a, b, c are collinear and d on their line). It is
/// the determinant | ax-dx, ay-dy, (ax-dx)^2+(ay-dy)^2 ; b.. ; c.. |. The sign is exact for all
/// finite inputs, with the same adaptive scheme as orient2d (the big-integer case begins at a span
/// of 265 binary orders of magnitude). The magnitude approximates the determinant. A NaN or
/// infinite coordinate gives NaN.
double incircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                const Eigen::Vector2d& d);

/// incircle on raw (x, y) pairs: a, b, c and d each point to two doubles.
double incircle(const double* a, const double* b, const double* c, const double* d);

namespace detail {

/// orient2d without the floating-point filter: always exact arithmetic (expansions, or a big
/// integer when the inputs need it). For tests and for cross-checking the filter.
double orient2d_exact(const double* a, const double* b, const double* c);

/// incircle without the floating-point filter (see orient2d_exact).
double incircle_exact(const double* a, const double* b, const double* c, const double* d);

/// orient2d evaluated with big integers only (slow; for tests of the other paths).
double orient2d_big_integer(const double* a, const double* b, const double* c);

/// incircle evaluated with big integers only (slow; for tests of the other paths).
double incircle_big_integer(const double* a, const double* b, const double* c, const double* d);

}  // namespace detail

}  // namespace floorgrid
