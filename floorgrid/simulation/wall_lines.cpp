#include "floorgrid/simulation/wall_lines.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "floorgrid/simulation/drawing_raster.hpp"
#include "floorgrid/simulation/wall_solids.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr double kDuplicateAngle = 3.0 * std::numbers::pi / 180.0;
constexpr double kDuplicateOffset = 3.0;  // pixels

double distance_to_line(const Eigen::Vector2d& p, const WallLine& line) {
  const Eigen::Vector2d u = line.along();
  const Eigen::Vector2d d = p - line.a;
  return std::abs(u.x() * d.y() - u.y() * d.x());
}

// Whether `shorter` lies along `longer` (nearly parallel, both ends near its line, overlapping).
bool duplicates(const WallLine& shorter, const WallLine& longer, double pixel) {
  const double angle = std::acos(std::min(1.0, std::abs(shorter.along().dot(longer.along()))));
  if (angle > kDuplicateAngle)
    return false;
  if (distance_to_line(shorter.a, longer) > kDuplicateOffset * pixel ||
      distance_to_line(shorter.b, longer) > kDuplicateOffset * pixel)
    return false;
  const Eigen::Vector2d u = longer.along();
  const double s0 = (shorter.a - longer.a).dot(u), s1 = (shorter.b - longer.a).dot(u);
  const double overlap =
      std::min(std::max(s0, s1), longer.length()) - std::max(std::min(s0, s1), 0.0);
  return overlap > 0.5 * shorter.length();
}

}  // namespace

std::vector<WallLine> find_wall_lines(const cv::Mat& ink, const GridGeometry& g,
                                      double min_length) {
  const cv::Mat centres = stroke_centres(ink);
  cv::Mat depth;
  cv::distanceTransform(ink, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const double pixels = min_length / g.resolution;
  std::vector<cv::Vec4i> found;
  cv::HoughLinesP(centres, found, 1.0, std::numbers::pi / 360.0,
                  std::max(10, static_cast<int>(pixels / 3)), pixels, 2.0);
  std::vector<WallLine> lines;
  for (const cv::Vec4i& f : found) {
    WallLine line;
    line.a = g.cell_center(f[0], f[1]);
    line.b = g.cell_center(f[2], f[3]);
    const cv::Point mid((f[0] + f[2]) / 2, (f[1] + f[3]) / 2);
    const float d = depth.at<float>(mid);
    line.half_width = std::max(0.5, d - 0.5) * g.resolution;
    lines.push_back(line);
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const WallLine& x, const WallLine& y) { return x.length() > y.length(); });
  std::vector<WallLine> kept;
  for (const WallLine& line : lines) {
    const bool seen = std::any_of(kept.begin(), kept.end(), [&](const WallLine& k) {
      return duplicates(line, k, g.resolution);
    });
    if (!seen)
      kept.push_back(line);
  }
  return kept;
}

bool has_on_both_sides(const WallLine& line, const cv::Mat& mask, const GridGeometry& g,
                       double offset, double fraction) {
  const Eigen::Vector2d u = line.along(), n = left_of(u);
  const int samples = std::max(4, static_cast<int>(line.length() / 0.1));
  int both = 0;
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector2d p = line.a + (line.b - line.a) * ((i + 0.5) / samples);
    const double reach = line.half_width + offset;
    both += is_set(mask, pixel_of(g, p + n * reach)) && is_set(mask, pixel_of(g, p - n * reach));
  }
  return both >= fraction * samples;
}

double ink_fraction(const WallLine& line, const cv::Mat& ink, const GridGeometry& g, double from,
                    double to) {
  const Eigen::Vector2d u = line.along();
  const int samples = std::max(2, static_cast<int>((to - from) / (g.resolution / 2)));
  int on = 0;
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector2d p = line.a + u * (from + (to - from) * (i + 0.5) / samples);
    // Within a pixel of the centre line: a diagonal line's centre wanders by a pixel.
    bool hit = false;
    for (int dy = -1; dy <= 1 && !hit; ++dy) {
      for (int dx = -1; dx <= 1 && !hit; ++dx)
        hit = is_set(ink, pixel_of(g, p) + cv::Point(dx, dy));
    }
    on += hit;
  }
  return double(on) / samples;
}

double dominant_angle(const std::vector<WallLine>& lines) {
  // Directions modulo a quarter turn, as angles times 4 on the circle.
  double c = 0.0, s = 0.0;
  for (const WallLine& line : lines) {
    const Eigen::Vector2d u = line.along();
    const double a = 4.0 * std::atan2(u.y(), u.x());
    c += line.length() * std::cos(a);
    s += line.length() * std::sin(a);
  }
  if (c == 0.0 && s == 0.0)
    return 0.0;
  double angle = std::atan2(s, c) / 4.0;
  if (angle < 0.0)
    angle += std::numbers::pi / 2;
  return angle;
}

}  // namespace floorgrid::plan_world
