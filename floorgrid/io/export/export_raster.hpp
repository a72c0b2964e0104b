#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>

#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid::io {

/// Image coordinates as GDAL counts them (pixel, line): (0, 0) is the top-left corner of the
/// top-left pixel, x right, y down; a pixel's centre is at (col + 0.5, row + 0.5). The map YAML's
/// origin is the outer corner of the lower-left pixel (ROS map_server), so image point (u, v) is
/// origin + R(yaw) * resolution * (u, height - v) in the frame.
Eigen::Vector2d image_to_frame(const GridGeometry& geometry, const Eigen::Vector2d& pixel_line);

/// The inverse of image_to_frame: a point of the frame (metres) in GDAL pixel/line.
Eigen::Vector2d frame_to_image(const GridGeometry& geometry, const Eigen::Vector2d& point);

/// image_to_frame as a homogeneous 3x3 matrix (T_frame_image).
Eigen::Matrix3d T_frame_image(const GridGeometry& geometry);

/// The maps an export may draw on beside the model, in the model's frames: the gridmap image,
/// and the plan as a raster (a map YAML or bare image) or as DXF geometry.
struct ExportMaps {
  std::optional<MapRaster> gridmap;            ///< the robot's map image
  std::optional<MapRaster> plan_raster;        ///< a raster plan's image (none for DXF)
  std::optional<OccupancyGrid> plan_grid;      ///< a raster plan's cells (walls = occupied)
  std::optional<VectorFloorplan> plan_vector;  ///< a DXF plan in plan metres (as the model's)
};

}  // namespace floorgrid::io
