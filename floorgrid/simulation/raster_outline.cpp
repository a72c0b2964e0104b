#include "floorgrid/simulation/raster_outline.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace floorgrid {

std::vector<std::vector<cv::Point>> simplified_outlines(const cv::Mat& mask, double tolerance) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  for (auto& contour : contours) {
    std::vector<cv::Point> simple;
    cv::approxPolyDP(contour, simple, tolerance, true);
    contour = std::move(simple);
  }
  return contours;
}

std::vector<Eigen::Vector2d> outline_corners(const std::vector<std::vector<cv::Point>>& outlines,
                                             const RasterFrame& frame) {
  std::vector<Eigen::Vector2d> corners;
  for (const auto& contour : outlines) {
    const std::size_t n = contour.size();
    if (n < 3)
      continue;
    for (std::size_t i = 0; i < n; ++i) {
      const cv::Point& p = contour[i];
      const cv::Point a = contour[(i + n - 1) % n] - p;
      const cv::Point b = contour[(i + 1) % n] - p;
      const double la = std::hypot(a.x, a.y), lb = std::hypot(b.x, b.y);
      if (la < 3.0 || lb < 3.0)
        continue;
      const double cosine = (a.x * b.x + a.y * b.y) / (la * lb);
      if (std::abs(cosine) <= 0.5)
        corners.push_back(frame.centre(p));
    }
  }
  return corners;
}

std::vector<Segment> outline_segments(const std::vector<std::vector<cv::Point>>& outlines,
                                      const RasterFrame& frame, int layer) {
  std::vector<Segment> segments;
  for (const auto& contour : outlines) {
    const std::size_t n = contour.size();
    if (n == 1) {
      // A lone pixel: a dot the laser can still hit, as a tiny square.
      const Eigen::Vector2d c = frame.centre(contour[0]);
      const double r = frame.pixel / 2;
      const Eigen::Vector2d corners[4] = {c + Eigen::Vector2d(-r, -r), c + Eigen::Vector2d(r, -r),
                                          c + Eigen::Vector2d(r, r), c + Eigen::Vector2d(-r, r)};
      for (int k = 0; k < 4; ++k)
        segments.push_back({corners[k], corners[(k + 1) % 4], layer});
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const cv::Point& a = contour[i];
      const cv::Point& b = contour[(i + 1) % n];
      if (n == 2 && i == 1)
        break;  // a two-point outline is one edge
      segments.push_back({frame.centre(a), frame.centre(b), layer});
    }
  }
  return segments;
}

}  // namespace floorgrid
