#include "floorgrid/simulation/room_segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "floorgrid/simulation/drawing_raster.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr double kMinCoreArea = 0.25;  // square metres: smaller cores are noise, not rooms
constexpr double kSnapRange = 0.6;     // metres: an opening is looked for this far either side
constexpr double kWallBehind = 0.25;   // metres of wall behind each jamb of a doorway
constexpr double kRaggedness = 0.05;   // metres a drawn wall's face may wander

// Every inside pixel joins the core it reaches first (4-connected breadth-first growth).
void grow_cores(const cv::Mat& inside, cv::Mat& labels) {
  std::vector<int> frontier;
  const int w = labels.cols, h = labels.rows;
  for (int y = 0; y < h; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = 0; x < w; ++x) {
      if (row[x] >= 0)
        frontier.push_back(y * w + x);
    }
  }
  int* l = labels.ptr<int>(0);
  const std::uint8_t* in = inside.ptr<std::uint8_t>(0);
  for (std::size_t head = 0; head < frontier.size(); ++head) {
    const int i = frontier[head];
    const int x = i % w, y = i / w;
    const int neighbours[4] = {x > 0 ? i - 1 : -1, x + 1 < w ? i + 1 : -1, y > 0 ? i - w : -1,
                               y + 1 < h ? i + w : -1};
    for (const int j : neighbours) {
      if (j >= 0 && in[j] != 0 && l[j] < 0) {
        l[j] = l[i];
        frontier.push_back(j);
      }
    }
  }
}

// Lines closing the openings that walls' free ends face: from the end of a wall (one going on
// for half a metre behind it), along its direction across free space to the next wall, when
// that is 0.5 to `max_length` metres away and the way lies inside. Facing jambs close a door
// in a wall, an end facing another wall's side a door beside it.
cv::Mat door_lines(const WallSolids& s, const GridGeometry& g, double max_length) {
  cv::Mat lines(s.walls.size(), CV_8UC1, cv::Scalar(0));
  cv::Mat open;
  cv::bitwise_not(s.walls, open);
  const double h = g.resolution;
  for (int y = 0; y < s.ends.rows; ++y) {
    for (int x = 0; x < s.ends.cols; ++x) {
      const cv::Vec2f v = s.ends.at<cv::Vec2f>(y, x);
      if (v[0] == 0.0f && v[1] == 0.0f)
        continue;
      const Eigen::Vector2d d(v[0], v[1]);
      const Eigen::Vector2d e = g.cell_center(x, y);
      bool wall_behind = true;
      for (double back = 0.1; back <= 0.5 && wall_behind; back += 0.1)
        wall_behind = is_set(s.walls, pixel_of(g, e - d * back));
      if (!wall_behind)
        continue;
      const Eigen::Vector2d start = e + d * run_length(s.walls, g, e, d, 1.0);
      // A ray three pixels wide: an end's direction may be off by a degree or two.
      const Eigen::Vector2d side = left_of(d) * h;
      const double free = std::min({run_length(open, g, start, d, max_length),
                                    run_length(open, g, start + side, d, max_length),
                                    run_length(open, g, start - side, d, max_length)});
      if (free < 0.5 || free >= max_length)
        continue;
      int inside = 0, samples = 0;
      for (double t = h; t < free; t += h, ++samples)
        inside += is_set(s.inside, pixel_of(g, start + d * t));
      if (inside < 0.8 * samples)
        continue;
      cv::line(lines, pixel_of(g, start), pixel_of(g, start + d * (free + h)), cv::Scalar(255), 2,
               cv::LINE_8);
    }
  }
  return lines;
}

// Labels the regions: the inside split by the door lines falls into cores (farther than
// core_radius pixels from its edge) and pieces no core reaches; every pixel joins the core it
// reaches first, then the door lines join a side.
int label_regions(const cv::Mat& inside, const cv::Mat& barriers, double core_radius, double h,
                  double min_area, cv::Mat& labels) {
  cv::Mat split = inside & ~barriers;
  cv::Mat depth;
  cv::distanceTransform(split, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::Mat cores, core_labels, stats, centroids;
  cv::compare(depth, core_radius, cores, cv::CMP_GT);
  const int n = cv::connectedComponentsWithStats(cores, core_labels, stats, centroids, 8, CV_32S);
  std::vector<int> region_of_core(static_cast<std::size_t>(n), -1);
  int regions = 0;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) * h * h >= kMinCoreArea)
      region_of_core[static_cast<std::size_t>(i)] = regions++;
  }
  labels = cv::Mat(inside.size(), CV_32S, cv::Scalar(-1));
  for (int y = 0; y < labels.rows; ++y) {
    const int* c = core_labels.ptr<int>(y);
    int* l = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x)
      l[x] = region_of_core[static_cast<std::size_t>(c[x])];
  }
  grow_cores(split, labels);
  cv::Mat left = (labels < 0) & split;
  const int m = cv::connectedComponentsWithStats(left, core_labels, stats, centroids, 4, CV_32S);
  std::vector<int> region_of_piece(static_cast<std::size_t>(m), -1);
  for (int i = 1; i < m; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) * h * h >= min_area)
      region_of_piece[static_cast<std::size_t>(i)] = regions++;
  }
  for (int y = 0; y < labels.rows; ++y) {
    const int* c = core_labels.ptr<int>(y);
    int* l = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (c[x] > 0)
        l[x] = region_of_piece[static_cast<std::size_t>(c[x])];
    }
  }
  grow_cores(inside, labels);
  return regions;
}

std::vector<WorldRegion> describe_regions(const cv::Mat& labels, const cv::Mat& depth, int count,
                                          const GridGeometry& g) {
  std::vector<WorldRegion> regions(static_cast<std::size_t>(count));
  std::vector<float> deepest(regions.size(), -1.0f);
  const double h = g.resolution;
  for (int y = 0; y < labels.rows; ++y) {
    const int* l = labels.ptr<int>(y);
    const float* d = depth.ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (l[x] < 0)
        continue;
      WorldRegion& r = regions[static_cast<std::size_t>(l[x])];
      const Eigen::Vector2d p = g.cell_center(x, y);
      r.area += h * h;
      r.box.extend(p);
      if (d[x] > deepest[static_cast<std::size_t>(l[x])]) {
        deepest[static_cast<std::size_t>(l[x])] = d[x];
        r.centre = p;
      }
    }
  }
  for (std::size_t i = 0; i < regions.size(); ++i) {
    WorldRegion& r = regions[i];
    char name[24];  // (GCC 12 warns falsely of overlap on "R" + std::to_string here)
    std::snprintf(name, sizeof name, "R%zu", i + 1);
    r.name = name;
    const double width = 2.0 * deepest[i] * h;  // of its widest part
    const double length = r.area / std::max(width, h);
    r.kind = length > 4.0 * width && width < 4.0 ? "corridor" : r.area > 150.0 ? "hall" : "room";
  }
  return regions;
}

// Contact points between regions (and with the outside), in doubled pixel coordinates.
using ContactMap = std::map<std::pair<int, int>, std::vector<std::pair<int, int>>>;

ContactMap find_contacts(const cv::Mat& labels, const cv::Mat& outside) {
  ContactMap contacts;
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const int a = labels.at<int>(y, x);
      if (a < 0)
        continue;
      const int steps[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
      for (int k = 0; k < 4; ++k) {
        const int nx = x + steps[k][0], ny = y + steps[k][1];
        if (nx < 0 || ny < 0 || nx >= labels.cols || ny >= labels.rows)
          continue;
        const int b = labels.at<int>(ny, nx);
        const std::pair<int, int> point{x + nx, y + ny};
        if (k < 2 && b >= 0 && b != a)
          contacts[{std::min(a, b), std::max(a, b)}].push_back(point);
        else if (b < 0 && outside.at<std::uint8_t>(ny, nx) != 0)
          contacts[{a, -1}].push_back(point);
      }
    }
  }
  return contacts;
}

// Groups contact points lying within two pixels of each other.
std::vector<std::vector<std::pair<int, int>>> cluster(
    const std::vector<std::pair<int, int>>& points) {
  std::vector<std::size_t> parent(points.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];
      i = parent[i];
    }
    return i;
  };
  std::unordered_map<std::int64_t, std::size_t> index;
  const auto key = [](int x, int y) { return (std::int64_t(x) << 32) ^ std::uint32_t(y); };
  for (std::size_t i = 0; i < points.size(); ++i)
    index.emplace(key(points[i].first, points[i].second), i);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int dy = -4; dy <= 4; ++dy) {
      for (int dx = -4; dx <= 4; ++dx) {
        const auto it = index.find(key(points[i].first + dx, points[i].second + dy));
        if (it != index.end())
          parent[root(it->second)] = root(i);
      }
    }
  }
  std::map<std::size_t, std::vector<std::pair<int, int>>> groups;
  for (std::size_t i = 0; i < points.size(); ++i)
    groups[root(i)].push_back(points[i]);
  std::vector<std::vector<std::pair<int, int>>> out;
  for (auto& [r, g] : groups)
    out.push_back(std::move(g));
  return out;
}

// The solids' complements an opening is measured on.
struct OpenSpace {
  cv::Mat open;        // not wall
  cv::Mat known_free;  // inside or outside
};

// Measures an opening from its contact points: the narrowest cross-section between walls
// near them, the walls' thickness and centre line at its ends.
Opening measure_opening(const std::vector<std::pair<int, int>>& points, int a, int b,
                        const WallSolids& s, const OpenSpace& space, const cv::Mat& labels,
                        const GridGeometry& g, const PlanWorldOptions& o) {
  const cv::Mat& open = space.open;
  const cv::Mat& known_free = space.known_free;
  Eigen::Matrix2Xd world(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    world.col(static_cast<Eigen::Index>(i)) =
        g.from_cell_coordinates({points[i].first / 2.0 + 0.5, points[i].second / 2.0 + 0.5});
  }
  const Eigen::Vector2d mean = world.rowwise().mean();
  const Eigen::Matrix2Xd centred = world.colwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> pca(centred * centred.transpose());
  Opening op;
  op.region_a = a;
  op.region_b = b;
  op.along = pca.eigenvectors().col(1);
  op.across = left_of(op.along);
  const cv::Point probe = pixel_of(g, mean - op.across * (1.5 * g.resolution));
  const bool a_behind = probe.x >= 0 && probe.y >= 0 && probe.x < labels.cols &&
                        probe.y < labels.rows && labels.at<int>(probe) == a;
  if (!a_behind)
    op.across = -op.across;
  const double extent = (op.along.transpose() * centred).cwiseAbs().maxCoeff();
  const double limit = extent + 1.0;
  // The narrowest cross-section within kSnapRange along the normal is the wall's line.
  double best = 2.0 * limit + 1.0, offset = 0.0;
  for (double t = -kSnapRange; t <= kSnapRange; t += g.resolution) {
    const Eigen::Vector2d c = mean + op.across * t;
    if (!is_set(open, pixel_of(g, c)))
      continue;
    const double span = run_length(open, g, c, op.along, limit) +
                        run_length(open, g, c, -op.along, limit) + std::abs(t) * 1e-3;
    if (span < best) {
      best = span;
      offset = t;
    }
  }
  Eigen::Vector2d c = mean + op.across * offset;
  const double ra = run_length(open, g, c, -op.along, limit);
  const double rb = run_length(open, g, c, op.along, limit);
  op.bounded = ra < limit && rb < limit;
  op.jamb_a = c - op.along * ra;
  op.jamb_b = c + op.along * rb;
  if (op.bounded) {
    // The wall at each end: its thickness and its centre line across the opening.
    double thickness = 0.0, shift = 0.0;
    const Eigen::Vector2d ends[2][2] = {{op.jamb_a, -op.along}, {op.jamb_b, op.along}};
    for (const auto& [jamb, out] : ends) {
      const Eigen::Vector2d inner = jamb + out * g.resolution;
      const double plus = run_length(s.walls, g, inner, op.across, 2.0);
      const double minus = run_length(s.walls, g, inner, -op.across, 2.0);
      thickness += (plus + minus) / 2;
      shift += (plus - minus) / 4;
    }
    op.wall_thickness = thickness;
    op.jamb_a += op.across * shift;
    op.jamb_b += op.across * shift;
    c += op.across * shift;
  }
  op.centre = (op.jamb_a + op.jamb_b) / 2;
  const double width = op.width();
  bool widens = true;
  for (const double side : {-1.0, 1.0}) {
    const Eigen::Vector2d q = c + op.across * side * (op.wall_thickness / 2 + 0.35);
    const double span = run_length(known_free, g, q, op.along, width + 1.0) +
                        run_length(known_free, g, q, -op.along, width + 1.0);
    widens = widens && span > width + 0.3;
  }
  // A doorway's jambs are ends of a wall that goes on behind them (not a stub standing in a
  // corridor, nor the side of a wall across it).
  // (Three parallel rays: a wall a SLAM map drew is ragged.)
  const auto wall_behind = [&](const Eigen::Vector2d& jamb, const Eigen::Vector2d& out) {
    double most = 0.0;
    for (const double side : {-kRaggedness, 0.0, kRaggedness}) {
      const Eigen::Vector2d from = jamb + out * g.resolution + op.across * side;
      most = std::max(most, run_length(s.walls, g, from, out, kWallBehind));
    }
    return most >= kWallBehind;
  };
  const bool walled =
      op.bounded && wall_behind(op.jamb_a, -op.along) && wall_behind(op.jamb_b, op.along);
  op.doorway = walled && widens && width >= o.doorway_width.min && width <= o.doorway_width.max;
  return op;
}

}  // namespace

RoomSegmentation segment_rooms(const WallSolids& solids, const GridGeometry& geometry,
                               const PlanWorldOptions& options) {
  const double h = geometry.resolution;
  cv::Mat depth;
  cv::distanceTransform(solids.inside, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  RoomSegmentation seg;
  const cv::Mat barriers = door_lines(solids, geometry, options.max_opening);
  const int count = label_regions(solids.inside, barriers, options.door_core_radius / h, h,
                                  options.min_region_area, seg.labels);
  seg.regions = describe_regions(seg.labels, depth, count, geometry);
  OpenSpace space;
  cv::bitwise_not(solids.walls, space.open);
  cv::bitwise_or(solids.inside, solids.outside, space.known_free);
  for (const auto& [key, points] : find_contacts(seg.labels, solids.outside)) {
    for (const auto& group : cluster(points)) {
      if (group.size() < 3)
        continue;
      seg.openings.push_back(measure_opening(group, key.first, key.second, solids, space,
                                             seg.labels, geometry, options));
    }
  }
  return seg;
}

}  // namespace floorgrid::plan_world
