#pragma once

// A drawing laid on a raster of the world, and the raster helpers the world builder shares
// (internal to simulation/).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/simulation/plan_dataset.hpp"

namespace floorgrid::plan_world {

/// A drawing on a raster of the world frame. Every mask of the world builder is CV_8U with
/// pixel (ix, iy) at row iy, column ix (rows counted from the bottom, as cells are), 255 where
/// true; `geometry` has yaw 0.
struct DrawingRaster {
  GridGeometry geometry;  ///< world metres
  cv::Mat ink;            ///< the drawing's ink
  cv::Mat unknown;        ///< where a raster drawing says nothing (its unknown cells)
};

/// Lays the drawing, scaled by `plan_scale` (world metres per plan metre), on a raster of the
/// world covering its ink and known cells plus `options.margin`, at `options.resolution` or
/// coarser to stay under `options.max_pixels`. A raster drawing is sampled at each pixel's
/// centre (and each of its occupied cells marks the pixel under its centre, so that no thin
/// stroke is lost); vector walls are drawn a pixel wide. InputError (field "plan") when the
/// drawing has no ink.
DrawingRaster rasterize_drawing(const PlanDrawing& drawing, double plan_scale,
                                const PlanWorldOptions& options);

/// The ink with strokes up to 2 `radius` metres apart joined into one wall (a closing): the
/// two faces a DXF draws of a wall become one solid.
cv::Mat join_strokes(const cv::Mat& ink, double radius, double resolution);

/// Euclidean distance, in pixels, from every pixel where `mask` is 0 to the nearest pixel
/// where it is set (0 on set pixels).
cv::Mat distance_to(const cv::Mat& mask);

/// The pixel holding a world point (may lie outside the raster).
cv::Point pixel_of(const GridGeometry& geometry, const Eigen::Vector2d& point);
/// Whether `p` lies in the mask and is set there.
bool is_set(const cv::Mat& mask, const cv::Point& p);
/// Sets (to `value`) every pixel of a convex outline (world metres).
void fill_outline(cv::Mat& mask, const GridGeometry& geometry,
                  const std::vector<Eigen::Vector2d>& outline, std::uint8_t value = 255);
/// Counts the pixels of a convex outline (world metres) and how many of them `mask` sets.
std::pair<int, int> outline_pixels(const cv::Mat& mask, const GridGeometry& geometry,
                                   const std::vector<Eigen::Vector2d>& outline);
/// The corners of a box centred at `centre` with `length` along unit `axis` and `depth` across.
std::vector<Eigen::Vector2d> oriented_box(const Eigen::Vector2d& centre,
                                          const Eigen::Vector2d& axis, double length, double depth);
/// A regular polygon of `sides` approximating a circle.
std::vector<Eigen::Vector2d> circle_outline(const Eigen::Vector2d& centre, double radius,
                                            int sides = 12);
/// Metres from `from` along unit `direction` while `mask` stays set (at most `limit`).
double run_length(const cv::Mat& mask, const GridGeometry& geometry, const Eigen::Vector2d& from,
                  const Eigen::Vector2d& direction, double limit);
/// The world points of every set pixel, one per column.
Eigen::Matrix2Xd set_pixels(const cv::Mat& mask, const GridGeometry& geometry);
/// A unit vector turned a quarter turn counter-clockwise.
inline Eigen::Vector2d left_of(const Eigen::Vector2d& v) {
  return {-v.y(), v.x()};
}

}  // namespace floorgrid::plan_world
