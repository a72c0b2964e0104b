#include "floorgrid/localization/resampling.hpp"

#include <cassert>

namespace floorgrid {

void systematic_resample(std::span<const double> weights, std::size_t count, double offset,
                         std::vector<std::size_t>& indices) {
  assert(offset >= 0.0 && offset < 1.0);
  indices.resize(count);
  const std::size_t n = weights.size();
  double total = 0.0;
  std::size_t last_positive = 0;
  for (std::size_t i = 0; i < n; ++i) {
    assert(weights[i] >= 0.0);
    total += weights[i];
    if (weights[i] > 0.0)
      last_positive = i;
  }
  assert(n > 0 && total > 0.0);
  const double step = total / static_cast<double>(count);
  std::size_t i = 0;
  double cumulative = weights.empty() ? 0.0 : weights[0];  // right end of particle i's slice
  for (std::size_t j = 0; j < count; ++j) {
    const double pointer = (offset + static_cast<double>(j)) * step;
    // Rounding may leave the last pointers just past the summed slices: they belong to the
    // last particle with weight, never to a trailing zero-weight one.
    while (pointer >= cumulative && i < last_positive)
      cumulative += weights[++i];
    indices[j] = i;
  }
}

void low_variance_resample(std::span<const double> weights, std::size_t count, Random& random,
                           std::vector<std::size_t>& indices) {
  systematic_resample(weights, count, random.uniform(), indices);
}

void gather_particles(const ParticleSet& from, std::span<const std::size_t> indices,
                      ParticleSet& to) {
  assert(&from != &to);
  const std::size_t count = indices.size();
  to.x.resize(count);
  to.y.resize(count);
  to.theta.resize(count);
  to.scale.resize(from.has_scale() ? count : 0);
  to.weight.assign(count, count > 0 ? 1.0 / static_cast<double>(count) : 0.0);
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t i = indices[j];
    to.x[j] = from.x[i];
    to.y[j] = from.y[i];
    to.theta[j] = from.theta[i];
  }
  if (from.has_scale()) {
    for (std::size_t j = 0; j < count; ++j)
      to.scale[j] = from.scale[indices[j]];
  }
}

}  // namespace floorgrid
