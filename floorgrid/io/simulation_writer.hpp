#pragma once

#include <filesystem>
#include <vector>

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

}  // namespace floorgrid::io
