#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Settings of the likelihood-field observation model. A beam whose endpoint lies d map metres
/// from the nearest occupied cell has likelihood
///   p(d) = z_hit * exp(-d^2 / (2 sigma_hit^2)) + z_rand,
/// in [z_rand, z_hit + z_rand]. Both parts are unnormalized (a share of the scan explained, not
/// a density), so z_rand is a floor no endpoint falls below whatever the range: one beam on
/// furniture the map lacks costs at most log((z_hit + z_rand) / z_rand) (2.3 with the defaults)
/// and never zeros a particle.
struct LikelihoodFieldOptions {
  /// Metres (map): spread of an endpoint about the wall it hit; covers range noise, the map's
  /// cells (0.05 m) and small SLAM distortions.
  double sigma_hit = 0.1;
  double z_hit = 0.9;   ///< weight of the Gaussian part, >= 0
  double z_rand = 0.1;  ///< the floor: likelihood of an endpoint far from every wall, > 0
  /// Metres (map): the distance field is capped here; beyond it the Gaussian part is 0 to float
  /// precision as long as max_distance >= 4 sigma_hit (exp(-8) = 3e-4 of the peak at 4 sigma).
  double max_distance = 2.0;
  /// Temperature: the scan's summed log-likelihood is multiplied by this (> 0). Neighbouring
  /// beams' errors are correlated (one misdrawn wall shifts many endpoints), so values below 1
  /// keep a filter from growing overconfident; 1 is the plain product of the beam likelihoods.
  double beam_weight = 1.0;
  /// Whether an endpoint in an unknown cell scores by its distance to the nearest occupied cell
  /// like one in a free cell (true), or gets the floor z_rand like one off the map (false).
  /// True by default: a SLAM gridmap draws walls as thin occupied lines with unknown space just
  /// behind, where noisy endpoints of beams that hit the wall land.
  bool unknown_is_free = true;
  /// Metres (map): an endpoint off the map, or farther than this from every observed (free or
  /// occupied) cell, says nothing about the fit (the map was cropped there, or never saw it):
  /// mean_beam_likelihood leaves it out. >= 0.
  double known_margin = 0.5;
  /// mean_beam_likelihood is NaN, "no information", when fewer than this share of a scan's
  /// endpoints are known, in [0, 1]: a robot driving off the map's edge is not lost.
  double min_known_share = 0.25;
};

/// Checks `options`; throws InputError naming the field (`likelihood_field.sigma_hit`, ...)
/// when one is out of range or not finite.
void validate_likelihood_field_options(const LikelihoodFieldOptions& options);

/// The likelihood-field observation model (Thrun, Burgard and Fox, Probabilistic Robotics 6.4;
/// SPEC: the default): each beam's endpoint scores by its distance to the nearest occupied cell,
/// ignoring what lies along the beam.
///
/// The construction precomputes, from the distance field, a table of log p per cell (float)
/// with a one-cell border holding the floor, so scoring one beam of one particle is a
/// transform of its robot-frame endpoint into cell coordinates (rotation and scale of the
/// particle and the grid's yaw folded into one 2x2 matrix per particle), a clamp into the
/// bordered table (every point off the map lands on the border) and a lookup: no branch, and
/// with AVX2 eight beams at a time by gather. Distances are measured between cell centres, so
/// an endpoint scores as the centre of its cell.
///
/// Immutable after construction; the const methods are safe to call from several threads.
class LikelihoodFieldModel : public ObservationModel {
 public:
  /// Builds the tables for `grid`. Throws InputError on bad options or a grid without cells.
  explicit LikelihoodFieldModel(const OccupancyGrid& grid,
                                const LikelihoodFieldOptions& options = {});

  /// Sum over the scan's beams of log p(d) of each endpoint, times options.beam_weight, for
  /// every particle. Particles are split into at most `threads` contiguous blocks, one per
  /// thread; each particle's value is computed alone, so the result is bit-identical for any
  /// `threads`. An empty scan gives 0 for every particle.
  void log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                      std::vector<double>& out, int threads = kDefaultThreads) const override;

  /// Mean over the scan's known endpoints (see known_margin) of exp(-d^2 / (2 sigma_hit^2)) at
  /// `pose` (the Gaussian part without weight or floor), in [0, 1]; NaN when fewer than
  /// min_known_share of the endpoints are known (an empty scan included). Known endpoints in
  /// unknown cells count 0 unless unknown_is_free.
  double mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                              double scale = 1.0) const override;

  /// Metres (map) from `point_in_map` to the nearest occupied cell (centre to centre, from the
  /// cell holding the point), capped at options.max_distance; the cap off the map.
  double distance_to_occupied(const Eigen::Vector2d& point_in_map) const;

  /// log p(d) of one endpoint at `point_in_map` (map frame, metres), as log_likelihood scores
  /// it before the temperature.
  double point_log_likelihood(const Eigen::Vector2d& point_in_map) const;

  /// The distance field to occupied cells (metres, capped at options.max_distance).
  const DistanceField& distance_field() const { return distance_; }
  /// Where the grid lies.
  const GridGeometry& geometry() const { return distance_.geometry(); }
  /// The options in use.
  const LikelihoodFieldOptions& options() const { return options_; }

 private:
  /// Per-particle affine map from robot-frame endpoints to bordered-table coordinates.
  struct CellTransform {
    float x0, y0;  // table coordinates of the particle's position
    float c, s;    // cos and sin of the heading in the grid, over (scale * resolution)
  };
  CellTransform cell_transform(const Pose2& pose, double scale) const;
  std::size_t table_index(const Eigen::Vector2d& point_in_map) const;

  LikelihoodFieldOptions options_;
  double cos_yaw_ = 1.0, sin_yaw_ = 0.0;  // of the grid's yaw
  DistanceField distance_;
  int stride_ = 0;                   // table row length: width + 2
  float max_u_ = 0.0f;               // width + 1: the right border column
  float max_v_ = 0.0f;               // height + 1: the top border row
  std::vector<float> log_p_;         // (width + 2) x (height + 2), border = log(z_rand)
  std::vector<float> gaussian_;      // same layout: exp(-d^2 / 2 sigma^2), border 0
  std::vector<std::uint8_t> known_;  // same layout: 1 within known_margin of an observed cell
};

}  // namespace floorgrid
