#include "floorgrid/geometry/residual_scale.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace floorgrid {
namespace {

// Beyond this median / cut the solution's sigma is several times the cut, and a few distances
// move it by a lot: the median of an even spread over the disc is 1 / sqrt(2) = 0.707 of it.
constexpr double kMaxMedianRatio = 0.69;

// The median of the first `count` distances (sorted partially).
double median(std::vector<double>& d, std::size_t count) {
  const auto mid = d.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(d.begin(), mid, d.begin() + static_cast<std::ptrdiff_t>(count));
  if (count % 2 == 1)
    return *mid;
  return 0.5 * (*mid + *std::max_element(d.begin(), mid));
}

}  // namespace

std::optional<double> truncated_rayleigh_scale(std::vector<double>& distances, double truncation,
                                               int parameters) {
  assert(truncation > 0.0 && parameters >= 0);
  const auto kept = std::partition(distances.begin(), distances.end(),
                                   [truncation](double d) { return d <= truncation; });
  const auto count = static_cast<std::size_t>(kept - distances.begin());
  if (count < static_cast<std::size_t>(parameters) + 2)
    return std::nullopt;
  const double ratio = median(distances, count) / truncation;
  if (!(ratio <= kMaxMedianRatio))
    return std::nullopt;
  if (ratio == 0.0)
    return 0.0;
  // With y = t^2 / (2 sigma^2) and rho = m / t, F(m) = F(t) / 2 reads
  // h(y) = 1 - 2 exp(-rho^2 y) + exp(-y) = 0. h < 0 just above 0 (slope 2 rho^2 - 1 < 0) and
  // h > 0 at ln 2 / rho^2 (the untruncated solution), with a single root between: bisect log y.
  const double rho2 = ratio * ratio;
  const auto h = [rho2](double y) { return 1.0 - 2.0 * std::exp(-rho2 * y) + std::exp(-y); };
  double lo = std::log(1e-3), hi = std::log(std::numbers::ln2 / rho2);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (h(std::exp(mid)) < 0.0 ? lo : hi) = mid;
  }
  const double sigma = truncation / std::sqrt(2.0 * std::exp(0.5 * (lo + hi)));
  const double k = static_cast<double>(count);
  return sigma * std::sqrt(2.0 * k / (2.0 * k - parameters));
}

}  // namespace floorgrid
