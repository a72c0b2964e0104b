#include "floorgrid/simulation/wall_solids.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "floorgrid/simulation/drawing_raster.hpp"

namespace floorgrid::plan_world {

namespace {

// Distance, in pixels, from every ink pixel to the paper (1 on a stroke's edge).
cv::Mat depth_in_stroke(const cv::Mat& ink) {
  cv::Mat depth;
  cv::distanceTransform(ink, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  return depth;
}

// The set pixels 8-connected to the raster's edge through set pixels.
cv::Mat reaching_edge(const cv::Mat& mask) {
  cv::Mat labels;
  const int count = cv::connectedComponents(mask, labels, 8, CV_32S);
  std::vector<std::uint8_t> edge(static_cast<std::size_t>(count), 0);
  for (int x = 0; x < labels.cols; ++x) {
    for (const int y : {0, labels.rows - 1}) {
      const int l = labels.at<int>(y, x);
      if (l > 0)
        edge[static_cast<std::size_t>(l)] = 255;
    }
  }
  for (int y = 0; y < labels.rows; ++y) {
    for (const int x : {0, labels.cols - 1}) {
      const int l = labels.at<int>(y, x);
      if (l > 0)
        edge[static_cast<std::size_t>(l)] = 255;
    }
  }
  cv::Mat out(mask.size(), CV_8UC1);
  for (int y = 0; y < labels.rows; ++y) {
    const int* l = labels.ptr<int>(y);
    auto* row = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x)
      row[x] = edge[static_cast<std::size_t>(l[x])];
  }
  return out;
}

// The stroke centres whose stroke is thinner than `thickness` pixels.
cv::Mat thin_centres(const cv::Mat& centres, const cv::Mat& depth, double thickness) {
  cv::Mat thin;
  // A centre at depth d lies in a stroke about 2 d - 1 pixels thick.
  cv::compare(depth, (thickness + 1.0) / 2.0, thin, cv::CMP_LT);
  cv::bitwise_and(thin, centres, thin);
  return thin;
}

}  // namespace

// A centre pixel is an end when the centre pixels near it lie on one straight line (an L
// corner or a junction does not), on one side of it, none ahead; it points along that line.
cv::Mat end_directions(const cv::Mat& centres) {
  constexpr int kReach = 8;           // pixels
  constexpr double kStraight = 0.15;  // the spread across the line over that along it, at most
  cv::Mat ends(centres.size(), CV_32FC2, cv::Scalar(0, 0));
  std::vector<Eigen::Vector2d> near;
  const auto gather = [&](const cv::Mat& mask, int x, int y) {
    near.clear();
    for (int dy = -kReach; dy <= kReach; ++dy) {
      for (int dx = -kReach; dx <= kReach; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || dx * dx + dy * dy > kReach * kReach || nx < 0 || ny < 0 ||
            nx >= mask.cols || ny >= mask.rows || mask.at<std::uint8_t>(ny, nx) == 0)
          continue;
        near.emplace_back(dx, dy);
      }
    }
  };
  for (int y = 0; y < centres.rows; ++y) {
    for (int x = 0; x < centres.cols; ++x) {
      if (centres.at<std::uint8_t>(y, x) == 0)
        continue;
      gather(centres, x, y);
      if (near.size() < 3)
        continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& q : near)
        mean += q / double(near.size());
      Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
      for (const auto& q : near)
        covariance += (q - mean) * (q - mean).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> pca(covariance);
      if (pca.eigenvalues()(0) > kStraight * pca.eigenvalues()(1))
        continue;
      Eigen::Vector2d out = pca.eigenvectors().col(1);
      const double along = mean.dot(out);
      if (std::abs(along) < 1.5)
        continue;  // neighbours on both sides
      if (along > 0.0)
        out = -out;
      const bool ahead = std::any_of(near.begin(), near.end(),
                                     [&](const Eigen::Vector2d& q) { return q.dot(out) > 0.5; });
      if (!ahead)
        ends.at<cv::Vec2f>(y, x) =
            cv::Vec2f(static_cast<float>(out.x()), static_cast<float>(out.y()));
    }
  }
  return ends;
}

namespace {

// Pixels within `radius` pixels of a set pixel of `seeds`, except beyond the ends of the
// centre lines: a wall grown from a stroke ends square where the stroke ends, not round half
// a wall further (which would narrow every door by the wall's thickness).
cv::Mat grown(const cv::Mat& seeds, double radius, const cv::Mat& ends) {
  cv::Mat inverse, distance, labels;
  cv::bitwise_not(seeds, inverse);
  cv::distanceTransform(inverse, distance, labels, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  // Each seed's label, and where that seed is.
  std::vector<cv::Point> seed_at(static_cast<std::size_t>(seeds.rows) * seeds.cols + 1);
  for (int y = 0; y < seeds.rows; ++y) {
    for (int x = 0; x < seeds.cols; ++x) {
      if (seeds.at<std::uint8_t>(y, x) != 0)
        seed_at[static_cast<std::size_t>(labels.at<int>(y, x))] = {x, y};
    }
  }
  cv::Mat near(seeds.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < seeds.rows; ++y) {
    for (int x = 0; x < seeds.cols; ++x) {
      if (distance.at<float>(y, x) > radius + 1e-4)  // (0.15 m / 0.025 m is 5.999...)
        continue;
      const cv::Point q = seed_at[static_cast<std::size_t>(labels.at<int>(y, x))];
      const cv::Vec2f out = ends.at<cv::Vec2f>(q);
      const double beyond = (x - q.x) * out[0] + (y - q.y) * out[1];
      if (beyond <= 0.5)
        near.at<std::uint8_t>(y, x) = 255;
    }
  }
  return near;
}

}  // namespace

cv::Mat stroke_centres(const cv::Mat& ink) {
  const cv::Mat depth = depth_in_stroke(ink);
  cv::Mat neighbourhood_max, centres;
  cv::dilate(depth, neighbourhood_max, cv::Mat());
  cv::compare(depth, neighbourhood_max, centres, cv::CMP_GE);
  cv::bitwise_and(centres, ink, centres);
  return centres;
}

WallSolids build_wall_solids(const cv::Mat& ink, const cv::Mat& unknown,
                             const WallThickness& thickness, double resolution,
                             const PlanWorldOptions& options) {
  const cv::Mat depth = depth_in_stroke(ink);
  const cv::Mat centres = stroke_centres(ink);
  cv::Mat ends = end_directions(centres);
  const double partition = thickness.partition / resolution;  // pixels
  const double exterior = thickness.exterior / resolution;
  // First every thin stroke as a partition, to find which walls face the outside.
  WallSolids first;
  cv::bitwise_or(ink, grown(thin_centres(centres, depth, partition), partition / 2, ends),
                 first.walls);
  split_inside(first, unknown, resolution, options.seal_radius, options.min_region_area);
  cv::Mat beyond;  // what lies beyond an outer wall: outside, or unknown reaching the edge
  // (not a blob the drawing left blank in a room)
  cv::bitwise_or(first.outside, reaching_edge(unknown), beyond);
  const cv::Mat to_beyond = distance_to(beyond);
  // A centre is an exterior wall's when the outside lies just past its (partition) face.
  const cv::Mat half_stroke = depth - 0.5;
  const cv::Mat reach = cv::max(half_stroke, partition / 2) + 2.0;
  cv::Mat outer_centres;
  cv::compare(to_beyond, reach, outer_centres, cv::CMP_LE);
  cv::bitwise_and(outer_centres, centres, outer_centres);
  cv::Mat inner_centres;
  cv::bitwise_not(outer_centres, inner_centres);
  cv::bitwise_and(inner_centres, centres, inner_centres);

  WallSolids solids;
  solids.walls = ink.clone();
  cv::bitwise_or(solids.walls,
                 grown(thin_centres(inner_centres, depth, partition), partition / 2, ends),
                 solids.walls);
  cv::bitwise_or(solids.walls,
                 grown(thin_centres(outer_centres, depth, exterior), exterior / 2, ends),
                 solids.walls);
  split_inside(solids, unknown, resolution, options.seal_radius, options.min_region_area);
  solids.ends = std::move(ends);
  return solids;
}

void split_inside(WallSolids& solids, const cv::Mat& unknown, double resolution, double seal_radius,
                  double min_area) {
  cv::Mat free;
  cv::bitwise_or(solids.walls, unknown, free);
  cv::bitwise_not(free, free);
  // The space far from every wall, and which of its pieces touch the raster's edge; unknown
  // reaching the edge (a raster's surroundings) is passable there, blank blobs in rooms not.
  cv::Mat passable;
  cv::bitwise_or(free, reaching_edge(unknown), passable);
  cv::Mat clearance;
  cv::distanceTransform(passable, clearance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const double seal = seal_radius / resolution;
  cv::Mat core;
  cv::compare(clearance, seal, core, cv::CMP_GT);
  const cv::Mat outside_core = reaching_edge(core);
  // Grown back by the seal radius, the outside reaches the walls but not through a sealed gap.
  cv::Mat near_outside;
  cv::compare(distance_to(outside_core), seal, near_outside, cv::CMP_LE);
  cv::bitwise_and(near_outside, free, solids.outside);
  cv::Mat inside;
  cv::bitwise_not(solids.outside, inside);
  cv::bitwise_and(inside, free, inside);
  // Small pieces (the hollow of a wall drawn with two lines, a shaft) are not rooms.
  cv::Mat labels, stats, centroids;
  const int pieces = cv::connectedComponentsWithStats(inside, labels, stats, centroids, 8, CV_32S);
  const double min_pixels = min_area / (resolution * resolution);
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(pieces), 0);
  for (int i = 1; i < pieces; ++i)
    keep[static_cast<std::size_t>(i)] = stats.at<int>(i, cv::CC_STAT_AREA) >= min_pixels ? 255 : 0;
  solids.inside = cv::Mat(inside.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    auto* row = solids.inside.ptr<std::uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x)
      row[x] = keep[static_cast<std::size_t>(label[x])];
  }
}

}  // namespace floorgrid::plan_world
