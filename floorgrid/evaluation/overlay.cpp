#include "floorgrid/evaluation/overlay.hpp"

#include <cmath>

namespace floorgrid {

void RgbImage::set(int col, int row, const Colour& colour) {
  if (col < 0 || row < 0 || col >= width || row >= height)
    return;
  const std::size_t i = (static_cast<std::size_t>(row) * width + col) * 3;
  rgb[i] = colour[0];
  rgb[i + 1] = colour[1];
  rgb[i + 2] = colour[2];
}

RgbImage grid_picture(const OccupancyGrid& grid) {
  RgbImage picture{grid.width(), grid.height(), {}};
  picture.rgb.resize(grid.geometry().size() * 3);
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      const CellState s = grid.state(ix, iy);
      const std::uint8_t v = s == CellState::occupied ? 0 : s == CellState::free ? 255 : 205;
      picture.set(ix, grid.geometry().image_row(iy), {v, v, v});
    }
  }
  return picture;
}

namespace {
void dot(RgbImage& picture, const GridGeometry& g, const Eigen::Vector2d& p, const Colour& colour,
         int radius) {
  const Eigen::Vector2d c = g.to_cell_coordinates(p);
  const int ix = static_cast<int>(std::floor(c.x())), iy = static_cast<int>(std::floor(c.y()));
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      if (dx * dx + dy * dy > radius * radius)
        continue;
      picture.set(ix + dx, g.image_row(iy + dy), colour);
    }
  }
}
}  // namespace

void draw_points(RgbImage& picture, const GridGeometry& geometry,
                 const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid, const Colour& colour,
                 int radius) {
  for (Eigen::Index i = 0; i < points_in_grid.cols(); ++i) {
    dot(picture, geometry, points_in_grid.col(i), colour, radius);
  }
}

void draw_plan(RgbImage& picture, const GridGeometry& geometry, const VectorFloorplan& plan,
               const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
               const Colour& colour, double spacing) {
  if (spacing <= 0.0)
    spacing = geometry.resolution / 2;
  const Eigen::Matrix2Xd samples = plan.sample_points(spacing);
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    dot(picture, geometry, plan_to_grid(samples.col(i)), colour, 0);
  }
}

}  // namespace floorgrid
