#pragma once

#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/localization/ray_marching.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Settings of the beam observation model (thesis 3.5.3, eq. 3.43-3.47). Ranges, sigma_hit,
/// lambda_unexpected and the max-range settings are in WORLD metres, the sensor's units: a
/// particle's expected range is ray cast in the map and multiplied by the particle's scale, so
/// the model is a density over what the laser measured and likelihoods of particles with
/// different scales compare fairly (in map metres each beam would carry a Jacobian 1/scale).
///
/// The four weights are normalized by their sum, so the mixture integrates to 1 over
/// [0, max range] whatever their scale.
struct BeamModelOptions {
  double weight_hit = 0.8;         ///< alpha: beams that hit the expected wall, >= 0
  double weight_unexpected = 0.1;  ///< beta: beams stopped short by what the map lacks, >= 0
  /// gamma: random readings, uniform over [0, max range]; > 0, so one bad beam never zeros
  /// a particle.
  double weight_random = 0.1;
  /// delta: max-range readings. 0 by default: a ScanObservation holds only returns (readings
  /// below the scan's max range; "no return" beams are only counted), so this part can only
  /// reward returns within max_window of the max range. Kept for completeness and for callers
  /// that set max_range below the laser's, which turns longer returns into max readings.
  double weight_max = 0.0;
  /// Metres: standard deviation of a hit about the expected range (eq. 3.43): range noise,
  /// cells of 0.05 m and small map distortions.
  double sigma_hit = 0.1;
  /// 1/metre: rate of the exponential of unexpected short readings (eq. 3.46); the mean
  /// distance of an unexpected obstacle (furniture, people) is 1 / lambda = 2 m.
  double lambda_unexpected = 0.5;
  /// Metres: z_max of eq. 3.44-3.45. 0 (the default) takes each scan's max_range; a positive
  /// value overrides it, and longer ranges are then read as max readings (clamped to it).
  double max_range = 0.0;
  /// Metres: width of the max-range part below the max range (eq. 3.45: |z - z_max| < 0.1);
  /// its density there is 1 / max_window.
  double max_window = 0.1;
  /// Temperature: the scan's summed log-likelihood is multiplied by this (> 0); see
  /// LikelihoodFieldOptions::beam_weight.
  double beam_weight = 1.0;
  /// Whether unknown cells stop the ray casting (GridRayCasterOptions); default free.
  bool unknown_is_occupied = false;
};

/// Checks `options`; throws InputError naming the field (`beam_model.sigma_hit`, ...) when one
/// is out of range or not finite.
void validate_beam_model_options(const BeamModelOptions& options);

/// The beam observation model of the thesis (3.5.3): each beam's expected range z_exp is ray
/// cast in the map from the particle's laser origin along the beam (GridRayCaster: exact cell
/// walk accelerated by a distance field), and the measured range z scores by the mixture
///   p(z) = alpha p_hit + beta p_unexp + gamma p_rand + delta p_max      (eq. 3.47)
/// with p_hit the Gaussian about z_exp normalized over [0, z_max] (eq. 3.43), p_unexp the
/// exponential lambda exp(-lambda z) on [0, z_exp) normalized there (eq. 3.46), p_rand = 1 /
/// z_max (eq. 3.44) and p_max = 1 / max_window on [z_max - max_window, z_max] (eq. 3.45).
/// A beam that meets no wall within z_max expects z_max. The mixture integrates to 1 over
/// [0, z_max], except when z_exp = 0 (the laser inside a blocking cell): p_unexp then has no
/// support and the mixture integrates to 1 - beta, a fair penalty for an impossible pose.
///
/// Immutable after construction; the const methods are safe to call from several threads.
class BeamModel : public ObservationModel {
 public:
  /// Prepares the ray casting in `grid`. Throws InputError on bad options or a grid without
  /// cells.
  explicit BeamModel(const OccupancyGrid& grid, const BeamModelOptions& options = {});

  /// Sum over the scan's beams of log p(z), times options.beam_weight, for every particle.
  /// Particles are split into at most `threads` contiguous blocks, one per thread; the result
  /// is bit-identical for any `threads`. An empty scan gives 0 for every particle. Throws
  /// InputError when neither the options nor the scan give a max range.
  void log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                      std::vector<double>& out, int threads = kDefaultThreads) const override;

  /// Mean over the scan's beams of exp(-(z - z_exp)^2 / (2 sigma_hit^2)) at `pose` (the hit
  /// part without normalization or weight), in [0, 1]; 0 for an empty scan.
  double mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                              double scale = 1.0) const override;

  /// The expected range of each beam of `scan` at `pose` with `scale`, world metres (the ray
  /// cast in map metres times scale; the max range when no wall is met within it).
  std::vector<double> expected_ranges(const ScanObservation& scan, const Pose2& pose,
                                      double scale = 1.0) const;

  /// The mixture density p(z) of eq. 3.47 (per world metre) of a range `range` given the
  /// expected range `expected_range` and the max range `max_range` (all world metres); 0
  /// outside [0, max_range].
  double beam_probability(double range, double expected_range, double max_range) const;

  /// The ray caster.
  const GridRayCaster& ray_caster() const { return caster_; }
  /// The options in use (weights as given, not normalized).
  const BeamModelOptions& options() const { return options_; }

 private:
  double max_range_for(const ScanObservation& scan) const;
  // eq. 3.47 for z in [0, z_max], given lambda exp(-lambda z).
  double mixture(double z, double z_exp, double z_max, double unexpected_at_z) const;

  BeamModelOptions options_;
  double w_hit_ = 0.0, w_unexpected_ = 0.0, w_random_ = 0.0, w_max_ = 0.0;  // normalized
  GridRayCaster caster_;
};

}  // namespace floorgrid
