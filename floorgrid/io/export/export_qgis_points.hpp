#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid::io {

/// How the pairs become QGIS Georeferencer control points.
struct QgisPointsOptions {
  /// Control points at most: more pairs are binned in the plan (reduce_pairs: a robust mean
  /// per cell), as the Georeferencer is meant for tens to hundreds of points, not 10^5.
  std::size_t max_points = 500;
};

/// What a .points file holds.
struct QgisPoints {
  std::string text;               ///< the file's bytes
  std::size_t points = 0;         ///< control points written
  std::size_t pairs = 0;          ///< pairs given
  bool source_in_pixels = false;  ///< sources are plan raster pixels, not plan metres
  double rms_m = 0.0;             ///< rms of the residuals written, metres
};

/// A QGIS Georeferencer `.points` file (the format QGIS's GCP list saves and loads): a first
/// line `#CRS: ` followed by nothing (what QGIS writes for no CRS: the robot's map frame is a
/// local engineering frame in metres, which QGIS then leaves untransformed), the header
/// `mapX,mapY,sourceX,sourceY,enable,dX,dY,residual` and one row per (binned) pair:
/// map = the pair's grid point (metres, robot map frame); source = the pair's plan point in the
/// plan raster's pixel coordinates as QGIS counts them for a raster without georeferencing
/// (x = GDAL pixel, y = -GDAL line: negative downwards) when `plan_raster` is given, else in
/// plan metres (a DXF plan); enable 1; dX, dY = model(plan) - grid in map units (metres, QGIS's
/// "map units" residual: transformed source minus map point) and residual = |(dX, dY)|.
/// QGIS recomputes the residuals on loading; these are the model's.
QgisPoints qgis_points(const PointMapping& model, const ReferencePairs& pairs,
                       const std::optional<GridGeometry>& plan_raster,
                       const QgisPointsOptions& options = {});

}  // namespace floorgrid::io
