#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/io/plans/plan_drawing.hpp"
#include "floorgrid/simulation/plan_dataset.hpp"

namespace floorgrid::io {

/// truth.json of a dataset made from a drawing: the format of a preset's (read_plan_truth
/// reads it), with "preset": "from-plan", the source, every choice made, the figures, the
/// world (regions, doors, glass, columns, furniture by kind, drawing errors, in plan metres)
/// and the true trajectory (world and grid frames).
nlohmann::json plan_dataset_truth_json(const PlanDataset& dataset, const PlanDrawingFile& source);

/// Writes a dataset made from the drawing `source` into `folder` (created if needed): the
/// drawing as given (a raster's image copied as floorplan.<ext> beside a floorplan.yaml whose
/// resolution and origin are divided by the plan scale; a DXF copied as floorplan.dxf), the
/// gridmap (gridmap.yaml/.pgm), log.carmen (noisy odometry), manual_pairs.csv, truth.json and
/// dataset.yaml (no start pose, floorplan_scale absent so `auto`, a DXF's units `auto` and its
/// wall layers, truth.warp and truth.manual_pairs); with `preview`, preview.png (the gridmap,
/// the drawing's ink through the exact warp in red, the path in green, manual pairs in blue)
/// and world.png (the world: walls black, glass cyan, door leaves orange, furniture brown,
/// columns and mullions purple, the drawing's ink light blue, the path green, drawing errors
/// magenta, unvisited regions pink). Every file is written atomically.
SimulationFiles write_plan_dataset(const PlanDataset& dataset, const PlanDrawingFile& source,
                                   const std::filesystem::path& folder, bool preview);

}  // namespace floorgrid::io
