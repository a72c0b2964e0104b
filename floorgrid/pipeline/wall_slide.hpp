#pragma once

#include <cstddef>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/pair_noise.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// How pairs are slid along their gridmap wall (see slide_pairs_along_walls).
struct WallSlideOptions {
  /// Rounds of fit-and-slide; 0 leaves the pairs as the filters made them.
  std::size_t iterations = 2;
  /// Metres: a pair's wall direction comes from the gridmap's occupied cells this near its
  /// grid point (at least two cells).
  double radius = 0.25;
  /// A pair has a wall direction when its wall's occupied cells scatter across the wall at
  /// most this share of along it (a straight wall: ~0; a corner or a blob: ~1), in (0, 1).
  double max_flatness = 0.25;
  /// The smooth model whose prediction a pair slides to (one of mapping_model_names()).
  std::string smoother = "gp";
  /// Pairs slide only when their own noise (differences between visits to one place, see
  /// pair_noise_along) is at least this many times larger along their walls than across
  /// (std ratio, >= 1): the premise of the slide, checked on the data. Pairs of real laser
  /// data show 1.6-2.6 (semi-real datasets from the Radish logs and fr079; fr079 on its real
  /// drawing 2.3), the simulator's 1.1-1.8.
  double min_along_ratio = 1.5;
};

/// Throws InputError naming `align.wall_slide.<field>` when an option is out of range.
void validate(const WallSlideOptions& options);

/// What slide_pairs_along_walls did.
struct WallSlide {
  ReferencePairs pairs;            ///< the pairs slid (the ones models are fitted on)
  std::size_t pairs_on_walls = 0;  ///< pairs with a wall direction (the ones that may slide)
  /// The pairs' own noise along and across their walls (nullopt: no place visited twice).
  std::optional<DirectionalPairNoise> noise;
  std::size_t iterations = 0;   ///< rounds done (0: no pair slid)
  double median_slide_m = 0.0;  ///< median distance a pair on a wall moved (grid metres)
  double p95_slide_m = 0.0;     ///< its 95th percentile

  /// Whether pairs slid (their noise was known and large enough along their walls, and the
  /// smoother could be fitted).
  bool applied() const { return iterations > 0; }
};

/// A pair's grid point is a laser endpoint on a gridmap wall. Across the wall both filters
/// place it to a few centimetres; along the wall (down a corridor) a filter's pose error is
/// larger (1.6-3.3 times against the truth on 21 semi-real datasets) and shared by every pair of
/// the scan and often of every visit, so interpolating models follow it. Each round fits
/// `options.smoother` (with `mapping`'s settings) to the current pairs and moves every pair on a
/// straight wall along that wall, and only along it, to where the smooth model puts its plan point;
/// pairs at corners and off the walls keep their grid points, and so anchor the walls' along
/// positions. The across-wall component of every pair is kept exactly. Pairs whose noise is not
/// clearly larger along their walls than across (options.min_along_ratio), or whose noise cannot be
/// measured, are returned as they are, as are pairs too few for the smoother. Deterministic.
/// InputError on bad options.
WallSlide slide_pairs_along_walls(const ReferencePairs& pairs, const OccupancyGrid& gridmap,
                                  const WallSlideOptions& options = {},
                                  const MappingOptions& mapping = {});

/// The unit direction of the gridmap's wall at `point_in_grid` (from the occupied cells within
/// `radius`), or zero where there is no straight wall there (see WallSlideOptions).
Eigen::Vector2d wall_direction(const OccupancyGrid& gridmap, const Eigen::Vector2d& point_in_grid,
                               double radius, double max_flatness);

}  // namespace floorgrid
