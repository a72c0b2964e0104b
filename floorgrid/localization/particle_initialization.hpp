#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/localization/particles.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// A range of plan scales (world metres per map metre) searched by global localization.
struct ScaleRange {
  double min = 1.0;  ///< > 0
  double max = 1.0;  ///< >= min
};

/// Throws InputError naming `scale_range.<field>` unless 0 < min <= max (finite).
void validate(const ScaleRange& range);

/// Where tracking starts: a Gaussian cloud around a known pose (thesis 4.6.1, "start with a
/// known pose and track it immediately").
struct TrackingStart {
  Pose2 pose;                   ///< the start pose, map frame (metres, radians)
  double position_sigma = 0.2;  ///< map metres, per axis (>= 0)
  double heading_sigma = 0.1;   ///< radians (>= 0)
  /// When set, the particles carry a scale drawn from N(scale, scale_sigma^2) (a fixed scale
  /// with scale_sigma 0); when not, they carry none (scale 1).
  std::optional<double> scale = std::nullopt;
  double scale_sigma = 0.0;  ///< standard deviation of the scale (>= 0)
};

/// Throws InputError naming `tracking_start.<field>` when a field is out of range.
void validate(const TrackingStart& start);

/// Which free cells global localization samples.
struct FreeSpaceOptions {
  /// Metres: > 0 keeps only free cells within this distance of an occupied cell (inside the
  /// building, not the open margin around a rasterized plan); 0 keeps every free cell.
  double max_wall_distance = 0.0;
};

/// Throws InputError naming `free_space.<field>` when a field is out of range.
void validate(const FreeSpaceOptions& options);

/// Uniform sampling over the free cells of an occupancy grid (in the grid's frame).
class FreeSpaceSampler {
 public:
  /// The candidate cells of `grid` per `options`. Throws InputError naming `free_space` when
  /// there is none.
  explicit FreeSpaceSampler(const OccupancyGrid& grid, const FreeSpaceOptions& options = {});

  /// Number of candidate cells.
  std::size_t cell_count() const { return cells_.size(); }
  /// Whether cell (ix, iy) is a candidate.
  bool is_candidate(int ix, int iy) const {
    return geometry_.contains(ix, iy) && mask_[static_cast<std::size_t>(iy) * geometry_.width + ix];
  }
  /// Area covered by the candidate cells, square metres.
  double area() const;
  /// A point uniform over the candidate cells (uniform cell, uniform within it), metres.
  Eigen::Vector2d sample_position(Random& random) const;
  /// The grid's geometry.
  const GridGeometry& geometry() const { return geometry_; }

 private:
  GridGeometry geometry_;
  std::vector<std::uint32_t> cells_;  // linear indices of the candidates
  std::vector<std::uint8_t> mask_;    // 1 for a candidate, per cell
};

/// `count` particles around `start` (weights 1 / count); headings wrapped to (-pi, pi], scales
/// kept > 0.
ParticleSet sample_tracking_start(const TrackingStart& start, std::size_t count, Random& random);

/// `count` particles for global localization (weights 1 / count): positions uniform over the
/// free space, headings uniform in [-pi, pi), and, when `scales` is given, scales uniform in
/// [scales->min, scales->max] (no scale otherwise).
ParticleSet sample_global(const FreeSpaceSampler& free_space, std::size_t count,
                          const std::optional<ScaleRange>& scales, Random& random);

/// Overwrites particles [begin, end) of `set` like sample_global (the scale only when the set
/// carries one: uniform over `scales`, or 1 without). Weights untouched.
void sample_free_space_particles(const FreeSpaceSampler& free_space,
                                 const std::optional<ScaleRange>& scales, Random& random,
                                 ParticleSet& set, std::size_t begin, std::size_t end);

/// Overwrites particles [begin, end) of `set` around `center`: positions uniform over the disc
/// of `radius` map metres, headings uniform within +-heading_spread of center.theta, and (when
/// the set carries one) scale from N(scale, scale_sigma^2), kept > 0. Weights untouched.
void sample_disc_particles(const Pose2& center, double radius, double heading_spread, double scale,
                           double scale_sigma, Random& random, ParticleSet& set, std::size_t begin,
                           std::size_t end);

/// How seed_best_hypotheses lays out and keeps its hypotheses.
struct HypothesisSeedingOptions {
  double position_step = 0.25;  ///< metres between lattice positions over the free space (> 0)
  int headings = 72;            ///< headings per position, evenly spaced (5 degrees; >= 1)
  int scales = 5;  ///< scales per position, evenly spaced over the range (>= 1; with a range)
  std::size_t keep = 10000;  ///< K: best hypotheses kept as particles (>= 1)
  /// Hypotheses scored at most (>= 1): a larger lattice is coarsened (position_step grows)
  /// until it fits, which bounds the cost whatever the map's size.
  std::size_t max_hypotheses = 20'000'000;
  std::size_t batch = 65536;  ///< hypotheses per observation-model call (bounds memory; >= 1)
  /// Spread every kept hypothesis uniformly over its lattice cell (+-step/2 in position, +-half
  /// a heading step, +-half a scale step), so that the particles cover the space between the
  /// lattice points the filter then refines.
  bool jitter = true;
};

/// Throws InputError naming `seeding.<field>` when a field is out of range.
void validate(const HypothesisSeedingOptions& options);

/// The particles seed_best_hypotheses chose, and how.
struct HypothesisSeeding {
  ParticleSet particles;                   ///< the K best hypotheses (jittered), weights 1 / K
  std::size_t scored = 0;                  ///< hypotheses scored
  double position_step = 0.0;              ///< metres: the lattice step used (after any coarsening)
  double best_log_likelihood = 0.0;        ///< of the best hypothesis
  double worst_kept_log_likelihood = 0.0;  ///< of the K-th best
  /// Each kept hypothesis's score (particle i's, best first), before the jitter.
  std::vector<double> log_likelihood;
};

/// Global localization by exhaustive scoring of the FIRST scan: every pose of a lattice over the
/// free space (positions `position_step` apart x `headings` headings x `scales` scales over
/// `scale_range` when given) is scored with `model`, and the K best become the particles.
/// A uniform cloud of N particles puts only ~N / (area * 2 pi / (dx dy dtheta)) of them near the
/// truth and loses it when the likelihood is peaked; scoring a dense lattice once and keeping
/// its best K concentrates the particles on every place the first scan fits (including the
/// symmetric look-alikes the next scans tell apart), far more reliably for the same cost.
/// The scan has then been used: the next filter step should carry the motion since it and the
/// next scan. O(hypotheses * beams) in `threads` threads; deterministic for `random`'s state.
/// Throws InputError on bad options.
HypothesisSeeding seed_best_hypotheses(const FreeSpaceSampler& free_space,
                                       const ScanObservation& scan, const ObservationModel& model,
                                       const HypothesisSeedingOptions& options,
                                       const std::optional<ScaleRange>& scale_range, Random& random,
                                       int threads = kDefaultThreads);

}  // namespace floorgrid
