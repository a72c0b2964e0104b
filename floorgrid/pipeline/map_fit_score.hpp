#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/maps/wall_surface_field.hpp"

namespace floorgrid {

/// A similarity from the gridmap frame into the plan frame: p = scale R(theta) g + t.
struct MapSimilarity {
  double scale = 1.0;  ///< plan metres per world metre (1 / floorplan_scale)
  double theta = 0.0;  ///< radians
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();  ///< plan metres

  /// A gridmap point in the plan.
  Eigen::Vector2d apply(const Eigen::Vector2d& g) const;
  /// A plan point in the gridmap.
  Eigen::Vector2d inverse(const Eigen::Vector2d& p) const;
  /// A gridmap pose in the plan (heading turned by theta).
  Pose2 apply(const Pose2& pose) const;
};

/// Whether two similarities are different answers: scales beyond 5% apart, turns beyond 10
/// degrees, or `centre` (a gridmap point) put beyond 2 world metres apart.
bool distinct(const MapSimilarity& a, const MapSimilarity& b, const Eigen::Vector2d& centre);

/// How well the gridmap's walls fit the plan's under a mapping.
struct MapFit {
  double score = 0.0;     ///< on_walls - in_free_space, in [-1, 1]
  double on_walls = 0.0;  ///< mean closeness of the gridmap's walls to the plan's walls, [0, 1]
  double in_free_space = 0.0;  ///< share of the plan's walls (over the gridmap's observed area)
                               ///< lying in space the gridmap saw free
};

/// A similarity with its fit.
struct ScoredSimilarity : MapFit {
  MapSimilarity transform;
};

/// How the plan grid's walls were drawn, which says where their surfaces are.
enum class PlanWalls {
  raster_strokes,  ///< a raster drawing: strokes of any thickness; the wall is the stroke's edge
  vector_lines,    ///< a vector drawing rasterized: the wall is the line along the cells' centres
};

/// How a dataset's plan grid was drawn: rasterized from `plan_geometry` (a DXF's lines) when
/// there is one, else a raster drawing.
inline PlanWalls plan_walls_of(const VectorFloorplan* plan_geometry) {
  return plan_geometry ? PlanWalls::vector_lines : PlanWalls::raster_strokes;
}

/// `points` evenly thinned to at most `max_points` (0: all).
std::vector<Eigen::Vector2d> evenly_thinned(const std::vector<Eigen::Vector2d>& points,
                                            std::size_t max_points);

/// Scores a mapping of the gridmap onto the plan (the registration's similarities, the maps-only
/// alignment's bent map) by one measure: the gridmap's wall points near the plan's wall
/// surfaces (a Gaussian closeness of width sigma, world metres), minus the share of the plan's
/// wall points, over the area the gridmap observed, that fall into space it saw free farther
/// than free_violation_distance from any of its walls (a wall the robot would have seen).
class MapFitScorer {
 public:
  /// Both maps' occupied cells, their wall points evenly thinned to `max_points` each.
  MapFitScorer(const OccupancyGrid& gridmap, const OccupancyGrid& plan, PlanWalls plan_walls,
               std::size_t max_points, double free_violation_distance);

  /// Whether both maps have at least 10 wall points.
  bool usable() const { return grid_points_.size() >= 10 && plan_points_.size() >= 10; }
  /// Scores on each map's cells thinned to `max_points` from now on (the centre stays).
  void use_points(std::size_t max_points);

  const OccupancyGrid& gridmap() const { return gridmap_; }  ///< the gridmap scored
  const OccupancyGrid& plan() const { return plan_; }        ///< the plan scored on
  const std::vector<Eigen::Vector2d>& grid_cells() const { return grid_cells_; }  ///< all
  const std::vector<Eigen::Vector2d>& plan_cells() const { return plan_cells_; }  ///< all
  /// The mean of the first thinned gridmap wall points (turns and scales pivot on it).
  const Eigen::Vector2d& centre() const { return centre_; }
  /// Plan metres to the plan's nearest wall surface (capped at 5).
  const WallSurfaceField& plan_field() const { return plan_field_; }

  /// The fit of a similarity.
  ScoredSimilarity score(const MapSimilarity& t, double sigma) const;

  /// The fit of any mapping: `grid_to_plan` and its inverse `plan_to_grid`, whose local scale
  /// (plan metres per world metre) is about `scale`.
  template <typename GridToPlan, typename PlanToGrid>
  MapFit score(const GridToPlan& grid_to_plan, const PlanToGrid& plan_to_grid, double scale,
               double sigma) const {
    MapFit fit;
    double on = 0.0;
    for (const Eigen::Vector2d& g : grid_points_) {
      const double d = plan_field_.distance(grid_to_plan(g)) / scale;
      on += std::exp(-0.5 * d * d / (sigma * sigma));
    }
    fit.on_walls = grid_points_.empty() ? 0.0 : on / double(grid_points_.size());
    std::size_t observed = 0, violations = 0;
    for (const Eigen::Vector2d& p : plan_points_)
      count_free_space(plan_to_grid(p), observed, violations);
    fit.in_free_space = observed ? double(violations) / double(observed) : 0.0;
    fit.score = fit.on_walls - fit.in_free_space;
    return fit;
  }

 private:
  // Counts a plan wall point put at `g` in the gridmap: observed there, and in free space far
  // from the gridmap's walls.
  void count_free_space(const Eigen::Vector2d& g, std::size_t& observed,
                        std::size_t& violations) const;

  const OccupancyGrid& gridmap_;
  const OccupancyGrid& plan_;
  std::vector<Eigen::Vector2d> grid_cells_;
  std::vector<Eigen::Vector2d> plan_cells_;
  WallSurfaceField plan_field_;
  DistanceField grid_field_;
  double free_violation_distance_ = 0.4;
  std::vector<Eigen::Vector2d> grid_points_;
  std::vector<Eigen::Vector2d> plan_points_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
};

}  // namespace floorgrid
