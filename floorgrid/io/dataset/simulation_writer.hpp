#pragma once

#include <filesystem>
#include <vector>

#include "floorgrid/simulation/log_dataset.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid::io {

/// What write_simulated_dataset wrote.
struct SimulationFiles {
  std::filesystem::path folder;              ///< the output folder
  std::vector<std::filesystem::path> files;  ///< every file written, in order
};

/// Writes a synthetic dataset into `folder` (created if needed): floorplan.dxf (layers WALLS,
/// DOORS, RACKS, in the preset's drawing units under its header units), gridmap.yaml/.pgm,
/// log.carmen, manual_pairs.csv, truth.json, dataset.yaml (floorplan_scale and floorplan_units
/// auto, both initial poses, truth.warp and truth.manual_pairs) and, with `preview`, preview.png:
/// the gridmap with the plan's walls drawn through the exact warp and the true path.
/// Every file is written atomically.
SimulationFiles write_simulated_dataset(const SimulatedDataset& dataset,
                                        const std::filesystem::path& folder, bool preview);

/// Writes a semi-real dataset made from the log `source` into `folder` (created if needed):
/// the plan as floorplan.yaml + floorplan.png (a raster with its map YAML) or, when
/// `dataset.plan_vector` holds walls, floorplan.dxf (metres, `$INSUNITS` m); gridmap.yaml/.pgm;
/// log.carmen (the corrected log); manual_pairs.csv; truth.json; dataset.yaml (no start pose,
/// floorplan_scale absent so `auto`, odometry_noise with the dataset's seed, truth.warp and
/// truth.manual_pairs) and, with `preview`, preview.png: the gridmap with the plan's walls
/// through the exact warp and the path. Every file is written atomically.
SimulationFiles write_log_dataset(const LogDataset& dataset, const std::string& source,
                                  const std::filesystem::path& folder, bool preview);

}  // namespace floorgrid::io
