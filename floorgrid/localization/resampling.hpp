#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/localization/particles.hpp"

namespace floorgrid {

/// Systematic (low-variance) resampling, the thesis's stochastic universal sampling (3.5.4):
/// every particle owns a slice of a wheel of circumference sum w proportional to its weight,
/// and `count` equally spaced pointers (offset + j) / count * sum w, j = 0..count-1, pick the
/// particles whose slices they hit. Particle i is picked floor(count w_i / sum w) or one more
/// time, and exactly count w_i / sum w times in expectation over a uniform offset; zero weights
/// are never picked. Writes `count` indices in ascending order to `indices` (resized; its
/// capacity is reused). `weights` need not be normalized but must sum to > 0; `offset` is in
/// [0, 1). O(N + count).
void systematic_resample(std::span<const double> weights, std::size_t count, double offset,
                         std::vector<std::size_t>& indices);

/// systematic_resample with the offset drawn uniformly from `random` (one draw).
void low_variance_resample(std::span<const double> weights, std::size_t count, Random& random,
                           std::vector<std::size_t>& indices);

/// Copies the particles `indices` of `from` into `to` (resized to indices.size(); `to` keeps a
/// scale array exactly when `from` has one) with equal weights 1 / indices.size(). `to` must
/// not be `from`; its buffers are reused, so a steady particle count allocates nothing.
void gather_particles(const ParticleSet& from, std::span<const std::size_t> indices,
                      ParticleSet& to);

}  // namespace floorgrid
