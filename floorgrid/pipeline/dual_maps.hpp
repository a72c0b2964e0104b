#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/localization/beam_model.hpp"
#include "floorgrid/localization/likelihood_field_model.hpp"
#include "floorgrid/localization/ray_marching.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/localization/wall_field.hpp"
#include "floorgrid/maps/visible_walls.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"

namespace floorgrid {

/// One map's observation model: the likelihood field always (global seeding scores millions of
/// hypotheses with it), and the beam model when chosen.
class MapModel {
 public:
  MapModel(const OccupancyGrid& map, const LikelihoodFieldOptions& likelihood,
           ObservationModelKind kind, const BeamModelOptions& beam);
  /// The chosen model.
  const ObservationModel& model() const;
  /// The likelihood field.
  const LikelihoodFieldModel& field() const { return *field_; }

 private:
  std::unique_ptr<LikelihoodFieldModel> field_;
  std::unique_ptr<BeamModel> beam_;
};

/// Both maps prepared for the dual localization: the plan as a robot inside sees it, each
/// map's observation model, walls to match scans onto, and how each filter prepares a scan.
/// Built once, read by every step.
class DualMaps {
 public:
  /// Prepares `inputs`' maps with `options`; what it decides goes to `notes`.
  DualMaps(const DualLocalizerInputs& inputs, const DualLocalizerOptions& options,
           std::vector<std::string>& notes);
  DualMaps(const DualMaps&) = delete;
  DualMaps& operator=(const DualMaps&) = delete;

  const OccupancyGrid& plan() const { return *plan_; }         ///< the plan the filters localize on
  const OccupancyGrid& gridmap() const { return gridmap_; }    ///< the robot's map
  const MapModel& plan_model() const { return plan_model_; }   ///< the plan filter's model
  const MapModel& grid_model() const { return grid_model_; }   ///< the gridmap filter's model
  const WallField& plan_walls() const { return plan_walls_; }  ///< the plan's walls
  const WallField& grid_walls() const { return grid_walls_; }  ///< the gridmap's walls
  /// The plan's ray caster for beam-consistent matching, or null when not used.
  const GridRayCaster* plan_rays() const { return plan_rays_ ? &*plan_rays_ : nullptr; }
  /// How a scan is prepared for the plan filter's model (each runner prepares its scans as it
  /// steps: a long log's prepared scans are not all held).
  const ObservationOptions& plan_observation_options() const { return plan_observation_; }
  /// How a scan is prepared for the gridmap filter's model.
  const ObservationOptions& grid_observation_options() const { return grid_observation_; }
  /// Scan i prepared for the gridmap filter's model.
  ScanObservation grid_observation(std::size_t i) const;

 private:
  VisibleWalls visible_;
  const OccupancyGrid* plan_;
  const OccupancyGrid& gridmap_;
  MapModel plan_model_, grid_model_;
  WallField plan_walls_, grid_walls_;
  std::optional<GridRayCaster> plan_rays_;
  const RobotLog& log_;
  ObservationOptions plan_observation_, grid_observation_;
};

/// Whether the scan matchers meet a raster plan's walls at its ink's edges
/// (DualLocalizerOptions::plan_wall_line): never for a vector plan; with automatic, where the
/// maps' faces fit (inputs.maps) found the partitions' faces at least ink_edge_min_offset world
/// metres off their strokes, saying so in `notes`.
bool plan_walls_at_ink_edges(const DualLocalizerInputs& inputs, const DualLocalizerOptions& options,
                             std::vector<std::string>& notes);

/// Reports progress every few scans (and at the last).
void report_progress(const DualProgressCallback& progress, const char* phase, std::size_t done,
                     std::size_t total, bool converged, std::size_t pairs = 0);

/// Counts one divergence of a filter under `reason`.
void count_divergence(DivergenceCount& count, const std::string& reason);

/// Seconds of wall clock since `start`.
double seconds_since(std::chrono::steady_clock::time_point start);

}  // namespace floorgrid
