#pragma once

// The outlines of a mask's regions as vector geometry (internal to simulation/).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// The outlines of a mask's set regions (outer boundaries and holes), through the centres of
/// their boundary pixels, simplified to `tolerance` pixels (Douglas-Peucker).
std::vector<std::vector<cv::Point>> simplified_outlines(const cv::Mat& mask, double tolerance);

/// Where a raster lies: pixel (x, y) is the square of side `pixel` metres whose lower-left
/// corner is `corner` + pixel * (x, y) (rows counted from the bottom, no yaw).
struct RasterFrame {
  Eigen::Vector2d corner = Eigen::Vector2d::Zero();  ///< metres
  double pixel = 0.05;                               ///< metres

  /// The centre of pixel (x, y), metres.
  Eigen::Vector2d centre(const cv::Point& p) const {
    return corner + pixel * Eigen::Vector2d(p.x + 0.5, p.y + 0.5);
  }
};

/// The outlines' corners: vertices turning by 60-120 degrees between edges of at least 3
/// pixels, in metres.
std::vector<Eigen::Vector2d> outline_corners(const std::vector<std::vector<cv::Point>>& outlines,
                                             const RasterFrame& frame);

/// The outlines' edges as segments of `layer`, in metres.
std::vector<Segment> outline_segments(const std::vector<std::vector<cv::Point>>& outlines,
                                      const RasterFrame& frame, int layer);

}  // namespace floorgrid
