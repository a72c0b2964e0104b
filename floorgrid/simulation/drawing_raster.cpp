#include "floorgrid/simulation/drawing_raster.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "floorgrid/core/error.hpp"
#include "floorgrid/maps/rasterize.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr int kShift = 4;  // fixed-point bits of the polygon corners handed to OpenCV
constexpr double kOne = 1 << kShift;

// The raster laid over `box` (world metres) plus the margin.
GridGeometry raster_over(const Eigen::AlignedBox2d& box, const PlanWorldOptions& o) {
  const Eigen::Vector2d size = box.sizes().array() + 2.0 * o.margin;
  const double finest = std::sqrt(size.x() * size.y() / o.max_pixels);
  GridGeometry g;
  g.resolution = std::max(o.resolution, finest);
  g.width = std::max(1, static_cast<int>(std::ceil(size.x() / g.resolution)));
  g.height = std::max(1, static_cast<int>(std::ceil(size.y() / g.resolution)));
  g.origin = {box.min().x() - o.margin, box.min().y() - o.margin, 0.0};
  return g;
}

DrawingRaster rasterize_cells(const OccupancyGrid& plan, double scale, const PlanWorldOptions& o) {
  const GridGeometry& pg = plan.geometry();
  // The known cells' extent, in the world.
  Eigen::AlignedBox2d known;
  std::size_t ink = 0;
  for (int iy = 0; iy < pg.height; ++iy) {
    for (int ix = 0; ix < pg.width; ++ix) {
      const CellState s = plan.state(ix, iy);
      if (s == CellState::unknown)
        continue;
      ink += s == CellState::occupied;
      for (const double dx : {0.0, 1.0}) {
        for (const double dy : {0.0, 1.0})
          known.extend(pg.from_cell_coordinates({ix + dx, iy + dy}) * scale);
      }
    }
  }
  if (ink == 0)
    throw InputError("the drawing has no walls: no occupied (dark) pixel", "", 0, "plan");
  DrawingRaster r;
  r.geometry = raster_over(known, o);
  const GridGeometry& g = r.geometry;
  r.ink = cv::Mat(g.height, g.width, CV_8UC1, cv::Scalar(0));
  r.unknown = cv::Mat(g.height, g.width, CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < g.height; ++iy) {
    auto* ink_row = r.ink.ptr<std::uint8_t>(iy);
    auto* unknown_row = r.unknown.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < g.width; ++ix) {
      int px = 0, py = 0;
      const CellState s = pg.cell_of(g.cell_center(ix, iy) / scale, px, py) ? plan.state(px, py)
                                                                            : CellState::unknown;
      ink_row[ix] = s == CellState::occupied ? 255 : 0;
      unknown_row[ix] = s == CellState::unknown ? 255 : 0;
    }
  }
  // A stroke thinner than a world pixel still marks the pixel under each of its cells.
  for (int iy = 0; iy < pg.height; ++iy) {
    for (int ix = 0; ix < pg.width; ++ix) {
      if (plan.state(ix, iy) != CellState::occupied)
        continue;
      const cv::Point p = pixel_of(g, pg.cell_center(ix, iy) * scale);
      if (p.x >= 0 && p.y >= 0 && p.x < g.width && p.y < g.height) {
        r.ink.at<std::uint8_t>(p) = 255;
        r.unknown.at<std::uint8_t>(p) = 0;
      }
    }
  }
  return r;
}

DrawingRaster rasterize_vector(const VectorFloorplan& plan, double scale,
                               const PlanWorldOptions& o) {
  if (plan.empty() || !(plan.total_length() > 0.0))
    throw InputError("the drawing has no walls: no line, arc or curve", "", 0, "plan");
  const VectorFloorplan world = plan.scaled(scale);
  DrawingRaster r;
  r.geometry = raster_over(world.bounds(), o);
  const GridGeometry& g = r.geometry;
  RasterizeOptions options;
  options.resolution = g.resolution;
  options.wall_thickness = 1.5 * g.resolution;  // a connected line, a pixel or so wide
  const OccupancyGrid grid = rasterize(world, options, g);
  r.ink = cv::Mat(g.height, g.width, CV_8UC1, cv::Scalar(0));
  r.unknown = cv::Mat(g.height, g.width, CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < g.height; ++iy) {
    auto* row = r.ink.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < g.width; ++ix)
      row[ix] = grid.state(ix, iy) == CellState::occupied ? 255 : 0;
  }
  return r;
}

std::vector<cv::Point> fixed_point(const GridGeometry& g,
                                   const std::vector<Eigen::Vector2d>& outline) {
  std::vector<cv::Point> points;
  points.reserve(outline.size());
  for (const auto& p : outline) {
    // OpenCV puts a pixel's centre at integer coordinates, we at half-integers.
    const Eigen::Vector2d c = g.to_cell_coordinates(p).array() - 0.5;
    points.emplace_back(static_cast<int>(std::lround(c.x() * kOne)),
                        static_cast<int>(std::lround(c.y() * kOne)));
  }
  return points;
}

}  // namespace

DrawingRaster rasterize_drawing(const PlanDrawing& drawing, double plan_scale,
                                const PlanWorldOptions& options) {
  return drawing.raster ? rasterize_cells(*drawing.raster, plan_scale, options)
                        : rasterize_vector(drawing.vector, plan_scale, options);
}

cv::Mat join_strokes(const cv::Mat& ink, double radius, double resolution) {
  const int r = static_cast<int>(std::lround(radius / resolution));
  if (r < 1)
    return ink.clone();
  cv::Mat joined;
  cv::morphologyEx(ink, joined, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}));
  return joined;
}

cv::Mat distance_to(const cv::Mat& mask) {
  cv::Mat inverse, distance;
  cv::bitwise_not(mask, inverse);
  cv::distanceTransform(inverse, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  return distance;
}

cv::Point pixel_of(const GridGeometry& geometry, const Eigen::Vector2d& point) {
  const Eigen::Vector2d c = geometry.to_cell_coordinates(point);
  return {static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y()))};
}

bool is_set(const cv::Mat& mask, const cv::Point& p) {
  return p.x >= 0 && p.y >= 0 && p.x < mask.cols && p.y < mask.rows &&
         mask.at<std::uint8_t>(p) != 0;
}

void fill_outline(cv::Mat& mask, const GridGeometry& geometry,
                  const std::vector<Eigen::Vector2d>& outline, std::uint8_t value) {
  const std::vector<cv::Point> points = fixed_point(geometry, outline);
  cv::fillConvexPoly(mask, points, cv::Scalar(value), cv::LINE_8, kShift);
}

std::pair<int, int> outline_pixels(const cv::Mat& mask, const GridGeometry& geometry,
                                   const std::vector<Eigen::Vector2d>& outline) {
  std::vector<cv::Point> points = fixed_point(geometry, outline);
  cv::Rect box = cv::boundingRect(points);
  box = cv::Rect(box.x / static_cast<int>(kOne) - 1, box.y / static_cast<int>(kOne) - 1,
                 box.width / static_cast<int>(kOne) + 3, box.height / static_cast<int>(kOne) + 3);
  const cv::Rect clipped = box & cv::Rect(0, 0, mask.cols, mask.rows);
  cv::Mat local(box.height, box.width, CV_8UC1, cv::Scalar(0));
  for (auto& p : points)
    p -= cv::Point(box.x * static_cast<int>(kOne), box.y * static_cast<int>(kOne));
  cv::fillConvexPoly(local, points, cv::Scalar(255), cv::LINE_8, kShift);
  const int total = cv::countNonZero(local);
  if (clipped.area() == 0)
    return {total, 0};
  cv::Mat both;
  cv::bitwise_and(local(clipped - cv::Point(box.x, box.y)), mask(clipped), both);
  return {total, cv::countNonZero(both)};
}

std::vector<Eigen::Vector2d> oriented_box(const Eigen::Vector2d& centre,
                                          const Eigen::Vector2d& axis, double length,
                                          double depth) {
  const Eigen::Vector2d u = axis * (length / 2), v = left_of(axis) * (depth / 2);
  return {centre - u - v, centre + u - v, centre + u + v, centre - u + v};
}

std::vector<Eigen::Vector2d> circle_outline(const Eigen::Vector2d& centre, double radius,
                                            int sides) {
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < sides; ++i) {
    const double a = 2 * std::numbers::pi * i / sides;
    out.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return out;
}

double run_length(const cv::Mat& mask, const GridGeometry& geometry, const Eigen::Vector2d& from,
                  const Eigen::Vector2d& direction, double limit) {
  const double step = geometry.resolution / 2;
  double s = 0.0;
  while (s < limit && is_set(mask, pixel_of(geometry, from + direction * (s + step))))
    s += step;
  return std::min(s, limit);
}

Eigen::Matrix2Xd set_pixels(const cv::Mat& mask, const GridGeometry& geometry) {
  Eigen::Matrix2Xd points(2, cv::countNonZero(mask));
  Eigen::Index k = 0;
  for (int iy = 0; iy < mask.rows; ++iy) {
    const auto* row = mask.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < mask.cols; ++ix) {
      if (row[ix] != 0)
        points.col(k++) = geometry.cell_center(ix, iy);
    }
  }
  return points;
}

}  // namespace floorgrid::plan_world
