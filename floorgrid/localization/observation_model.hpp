#pragma once

#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/localization/particles.hpp"
#include "floorgrid/localization/scan_observation.hpp"

namespace floorgrid {

/// p(scan | pose, map): how well a scan fits a map at a pose (thesis 3.5.3).
class ObservationModel {
 public:
  virtual ~ObservationModel() = default;

  /// The log-likelihood of `scan` for every particle, written to `out` (resized), summed over
  /// the scan's beams; uses at most `threads` threads (the result does not depend on it).
  virtual void log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                              std::vector<double>& out, int threads = kDefaultThreads) const = 0;

  /// The mean over the scan's beams of each beam's likelihood at one pose, in [0, 1]: the
  /// share of the scan the map explains there (1: every endpoint exactly on a wall). Used by
  /// the convergence and divergence tests; `scale` as in ScanObservation. NaN when the map
  /// cannot tell (too few beams end where the map knows anything): the tests then hold.
  virtual double mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                                      double scale = 1.0) const = 0;
};

}  // namespace floorgrid
