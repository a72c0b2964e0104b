#include "floorgrid/core/random.hpp"

#include <cassert>
#include <cmath>

namespace floorgrid {

std::int64_t Random::integer(std::int64_t lo, std::int64_t hi) {
  assert(hi >= lo);
  const std::uint64_t range = static_cast<std::uint64_t>(hi - lo) + 1;
  if (range == 0)
    return static_cast<std::int64_t>(engine_());  // the full 64-bit range
  // Rejection sampling: unbiased for any range.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
  std::uint64_t draw = 0;
  do {
    draw = engine_();
  } while (draw >= limit);
  return lo + static_cast<std::int64_t>(draw % range);
}

double Random::normal(double sigma) {
  if (has_spare_) {
    has_spare_ = false;
    return sigma * spare_normal_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = uniform(-1.0, 1.0);
    v = uniform(-1.0, 1.0);
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_ = true;
  return sigma * u * factor;
}

}  // namespace floorgrid
