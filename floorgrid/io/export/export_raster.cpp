#include "floorgrid/io/export/export_raster.hpp"

namespace floorgrid::io {

Eigen::Matrix3d T_frame_image(const GridGeometry& geometry) {
  // Cell coordinates (from the bottom row) are (u, height - v): a flip of the image's y axis.
  Eigen::Matrix3d T_cell_image = Eigen::Matrix3d::Identity();
  T_cell_image(1, 1) = -1.0;
  T_cell_image(1, 2) = geometry.height;
  Eigen::Matrix3d T_frame_cell = geometry.origin.matrix();
  T_frame_cell.topLeftCorner<2, 2>() *= geometry.resolution;
  return T_frame_cell * T_cell_image;
}

Eigen::Vector2d image_to_frame(const GridGeometry& geometry, const Eigen::Vector2d& pixel_line) {
  return geometry.from_cell_coordinates({pixel_line.x(), geometry.height - pixel_line.y()});
}

Eigen::Vector2d frame_to_image(const GridGeometry& geometry, const Eigen::Vector2d& point) {
  const Eigen::Vector2d cell = geometry.to_cell_coordinates(point);
  return {cell.x(), geometry.height - cell.y()};
}

}  // namespace floorgrid::io
