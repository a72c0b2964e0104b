#pragma once

#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/simulation/plan_truth.hpp"

namespace floorgrid {

/// How hand-picked pairs are emulated.
struct ManualPairsOptions {
  int min_pairs = 30;      ///< fewer only when fewer corners are visible in the gridmap
  int max_pairs = 60;      ///< at most
  double noise = 0.05;     ///< metres: radial standard deviation of the grid click (about a pixel)
  int visible_within = 1;  ///< cells: a corner is visible when an occupied cell is this close
};

/// Emulates an operator clicking wall corners in both maps: corners (world metres) whose true
/// grid position has an occupied gridmap cell within `visible_within` cells are candidates; a
/// random number of them in [min_pairs, max_pairs] are picked, each giving the exact plan point
/// (world x plan_scale) and the true grid point plus normal noise.
ReferencePairs emulate_manual_pairs(const std::vector<Eigen::Vector2d>& corners_in_world,
                                    const PlanTruth& truth, double plan_scale,
                                    const OccupancyGrid& gridmap, const ManualPairsOptions& options,
                                    Random& random);

}  // namespace floorgrid
