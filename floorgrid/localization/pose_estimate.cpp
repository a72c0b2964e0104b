#include "floorgrid/localization/pose_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {
namespace {

// A mean resultant length below this counts as headings spread evenly (see heading_std).
constexpr double kMinResultant = 1e-300;

}  // namespace

double effective_sample_size(std::span<const double> weights) {
  double sum = 0.0, sum_squares = 0.0;
  for (const double w : weights) {
    sum += w;
    sum_squares += w * w;
  }
  return sum_squares > 0.0 ? sum * sum / sum_squares : 0.0;
}

double circular_mean(std::span<const double> angles, std::span<const double> weights) {
  double s = 0.0, c = 0.0;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    s += w * std::sin(angles[i]);
    c += w * std::cos(angles[i]);
  }
  return s == 0.0 && c == 0.0 ? 0.0 : std::atan2(s, c);  // eq. 4.26
}

PoseEstimate estimate_pose(const ParticleSet& particles) {
  PoseEstimate e;
  const std::size_t n = particles.size();
  e.particles = n;
  if (n == 0)
    return e;
  const bool weighted = !particles.weight.empty();
  const bool scaled = particles.has_scale();

  double total = 0.0, sum_squares = 0.0, mx = 0.0, my = 0.0, s = 0.0, c = 0.0, ms = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weighted ? particles.weight[i] : 1.0;
    total += w;
    sum_squares += w * w;
    mx += w * particles.x[i];  // eq. 4.24
    my += w * particles.y[i];  // eq. 4.25
    s += w * std::sin(particles.theta[i]);
    c += w * std::cos(particles.theta[i]);
    if (scaled)
      ms += w * particles.scale[i];
  }
  if (!(total > 0.0))
    return e;
  mx /= total;
  my /= total;
  s /= total;
  c /= total;
  e.pose = {mx, my, s == 0.0 && c == 0.0 ? 0.0 : std::atan2(s, c)};  // eq. 4.26
  e.scale = scaled ? ms / total : 1.0;
  e.effective_sample_size = total * total / sum_squares;
  e.ess_ratio = e.effective_sample_size / static_cast<double>(n);

  // Second pass about the mean: no cancellation from large map coordinates.
  double cxx = 0.0, cxy = 0.0, cyy = 0.0, vs = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weighted ? particles.weight[i] : 1.0;
    const double dx = particles.x[i] - mx, dy = particles.y[i] - my;
    cxx += w * dx * dx;
    cxy += w * dx * dy;
    cyy += w * dy * dy;
    if (scaled) {
      const double ds = particles.scale[i] - e.scale;
      vs += w * ds * ds;
    }
  }
  cxx /= total;
  cxy /= total;
  cyy /= total;
  e.position_covariance << cxx, cxy, cxy, cyy;
  // Largest eigenvalue of a symmetric 2x2 matrix in closed form.
  const double half_trace = 0.5 * (cxx + cyy);
  const double radius = std::hypot(0.5 * (cxx - cyy), cxy);
  e.position_std = std::sqrt(std::max(0.0, half_trace + radius));
  const double resultant = std::clamp(std::hypot(s, c), kMinResultant, 1.0);
  e.heading_std = std::sqrt(std::max(0.0, -2.0 * std::log(resultant)));
  e.scale_std = scaled ? std::sqrt(vs / total) : 0.0;
  return e;
}

}  // namespace floorgrid
