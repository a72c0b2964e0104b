#pragma once

#include <string>
#include <vector>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// How a filter mask of the old map is carried onto the new map. Defaults in one place.
struct MaskMigrationOptions {
  /// K: the mask's non-zero cells are widened by K x the model's std_m at each boundary cell
  /// (only for masks whose values are all 0 or 100, keepout masks: a speed mask's values have
  /// no order the widening could respect).
  double margin_sigma = 2.0;
};

/// Checks the options; InputError naming `migrate.<field>`.
void validate(const MaskMigrationOptions& options);

/// A mask on the new map and what carrying it did.
struct MigratedMask {
  OccupancyGrid mask;                    ///< on the new geometry, the old mask's values
  std::size_t cells_not_invertible = 0;  ///< new cells the model could not map back: unknown
  std::size_t cells_off_old_mask = 0;    ///< new cells mapping back outside the old mask: unknown
  std::size_t cells_widened = 0;         ///< cells added by the margin
  bool widened = false;                  ///< whether a margin was applied
  std::vector<std::string> warnings;     ///< no std_m, values not binary, ...
};

/// The new map's cells resampled from `old_mask` (nearest old cell): each new cell centre mapped
/// back through `old_to_new`'s inverse into the old mask. Cells that cannot be mapped back, or
/// land off the old mask, are unknown (-1: nav2's keepout and speed filters leave them alone).
MigratedMask migrate_mask(const PointMapping& old_to_new, const OccupancyGrid& old_mask,
                          const GridGeometry& new_geometry,
                          const MaskMigrationOptions& options = {});

/// The new grid when no new map is given: the old mask's corners mapped forward, their bounding
/// box at the old mask's resolution, yaw 0.
GridGeometry migrated_geometry(const PointMapping& old_to_new, const GridGeometry& old_mask);

}  // namespace floorgrid
