#pragma once

#include <cstddef>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// A set of pose hypotheses in one map's frame, stored as parallel arrays (structure of arrays:
/// the observation models stream through them).
struct ParticleSet {
  std::vector<double> x;      ///< metres, map frame
  std::vector<double> y;      ///< metres, map frame
  std::vector<double> theta;  ///< radians, map frame
  /// World metres per map metre of each particle (a laser range r lies r / scale map metres
  /// away): the plan's scale as a particle state; empty means every particle has scale 1.
  std::vector<double> scale;
  std::vector<double> weight;  ///< normalized weights (sum 1), or empty before the first update

  /// Number of particles.
  std::size_t size() const { return x.size(); }
  /// Whether the particles carry a scale.
  bool has_scale() const { return !scale.empty(); }
  /// Scale of particle i (1 when the set has none).
  double scale_of(std::size_t i) const { return scale.empty() ? 1.0 : scale[i]; }
  /// Pose of particle i.
  Pose2 pose(std::size_t i) const { return {x[i], y[i], theta[i]}; }
  /// Resizes every array (scale only when the set has one).
  void resize(std::size_t n);
};

}  // namespace floorgrid
