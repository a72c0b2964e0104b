#pragma once

#include <Eigen/Core>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_fit_score.hpp"

namespace floorgrid {

/// How the 2-D correlation search of register_maps lays its lattice.
struct MapCorrelationOptions {
  double cell = 0.3;         ///< world metres per cell of the coarse images
  double closeness = 0.6;    ///< world metres: sigma of a plan wall's closeness at this level
  double scale_step = 0.04;  ///< relative step of the scale lattice
  int peaks = 12;            ///< candidates kept over all turns and scales
};

/// A pose and scale of the gridmap on the plan found by correlation, with its coarse score.
struct CorrelationCandidate {
  MapSimilarity transform;  ///< grid -> plan
  double score = 0.0;       ///< coarse on_walls - in_free_space
};

/// The inputs of the correlation search: each map's wall cell centres (its own frame), the
/// gridmap (its free and observed cells), the turns to try (radians, applied to the gridmap's
/// walls after turning them by -grid_angle; the plan's walls are turned by -plan_angle), the
/// scale range, and what counts as free space.
struct CorrelationInputs {
  const OccupancyGrid& gridmap;
  const std::vector<Eigen::Vector2d>& grid_walls;
  const std::vector<Eigen::Vector2d>& plan_walls;
  double grid_angle = 0.0;
  double plan_angle = 0.0;
  std::vector<double> turns;
  double min_scale = 0.25;
  double max_scale = 4.0;
  /// World metres from the gridmap's walls beyond which its free space counts against a plan
  /// wall (MapRegistrationOptions::free_violation_distance).
  double free_violation_distance = 0.4;
};

/// Candidates of the gridmap's pose and scale on the plan by a 2-D correlation, for every turn
/// and scale of the lattice, of coarse images (the wall profiles' 1-D search loses a partial or
/// bent map, whose profiles do not line up with a whole building's): the gridmap's wall cells
/// against the plan walls' closeness (exp(-d^2 / 2 closeness^2)), less the share of the plan's
/// walls that fall into space the gridmap saw free, over every shift at once (cv::matchTemplate).
/// Best first, no two within 5% of scale, 10 degrees and 2 world metres.
std::vector<CorrelationCandidate> correlation_candidates(const CorrelationInputs& inputs,
                                                         const MapCorrelationOptions& options = {});

}  // namespace floorgrid
