#pragma once

#include <optional>
#include <string>

#include "floorgrid/geometry/displacement_lattice.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/pipeline/map_registration.hpp"
#include "floorgrid/pipeline/wall_faces.hpp"

namespace floorgrid {

/// How the gridmap is aligned to the plan from the two maps alone (no robot run).
struct MapAlignmentOptions {
  /// World metres between the displacement lattice's nodes in the first stage; each later
  /// stage halves it down to last_spacing.
  double first_spacing = 8.0;
  double last_spacing = 2.0;  ///< world metres, the finest lattice
  /// World metres: a gridmap wall point is matched to a plan wall this near (first stage); the
  /// radius shrinks geometrically to last_radius in the finest stage.
  double first_radius = 1.0;
  double last_radius = 0.3;  ///< world metres
  int rounds = 3;            ///< correspondence rounds per stage
  double stiffness = 1.0;    ///< the lattice's membrane weight (DisplacementLattice::fit)
  /// World metres between the gridmap wall points used. 0.2 gave Seattle-2 and fr079-2
  /// (semi-real) 112 and 344 pairs and a best model 1.74x and 2.27x the run-based error; 0.1,
  /// 1.20x and 1.39x.
  double point_spacing = 0.1;
  double max_normal_angle = 30;  ///< degrees between matched walls' directions, at most
  /// World metres: the final correspondences this near their plan wall become the pairs.
  double pair_radius = 0.15;
  // The bars below were set on the Halmstad sensor maps (bench/halmstad_maps_only.sh with
  // negatives): the 32 maps on their own layouts, each on the two other buildings' (64).
  /// Accepted when the fitness (MapFit::score of the bent map) is at least this. The right
  /// alignments measured 0.26-0.70, the wrong ones -0.17 to 0.40: the ten above 0.2 are F5_01
  /// and F5_04 on E5 and small maps (HIH's) inside a large building, which min_on_walls and
  /// max_ambiguity catch.
  double min_fitness = 0.2;
  /// Not accepted either when fewer of the bent gridmap's walls than this lie on the plan's
  /// (MapFit::on_walls): a map that fits its own building explains most of its walls. The
  /// right alignments measured 0.43-0.76 (the semi-real ones 0.80-0.96); the ten wrong ones
  /// above min_fitness 0.29-0.42.
  double min_on_walls = 0.4;
  /// Not accepted either when the registration's best other place, bent as well, reaches this
  /// share of the fitness (MapAlignment::ambiguity): the maps do not tell where the gridmap
  /// is. The right alignments measured up to 0.85 (HIH_02: the small HIH maps fit their small
  /// building shrunk too); HIH_03 and HIH_04 on E5, the wrong ones that pass min_on_walls,
  /// 0.99 and 1.00.
  double max_ambiguity = 0.9;
  /// The registration's correlation_below here (> 1: its 2-D correlation search always runs:
  /// the wall profiles' 1-D search registered 12 of the 27 Halmstad sensor maps, with it all 27).
  double correlation_below = 2.0;
  /// The registration refined with where the laser meets the drawn walls, and the bend aimed
  /// at those faces (wall_faces.hpp).
  WallFaceOptions faces;
};

/// Checks `options`; throws InputError naming `<prefix><field>`.
void validate(const MapAlignmentOptions& options, const std::string& prefix = "align.maps_only.");

/// The gridmap mapped into the plan as the maps' alignment bent it: the registration's
/// similarity, then a smooth displacement lattice in the plan frame (world metres -> plan metres).
struct MapWarp {
  MapSimilarity similarity;  ///< the registration's similarity
  /// The displacement (plan metres) added after the similarity, as a function of its result.
  DisplacementLattice lattice{Eigen::AlignedBox2d(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones()),
                              1.0};
  int stages = 0;  ///< lattice stages fitted (0: the similarity alone)

  /// A gridmap point in the plan: similarity, then the lattice's displacement there.
  Eigen::Vector2d apply(const Eigen::Vector2d& g) const;
  /// A plan point in the gridmap: Newton steps on `apply` from its first-order inverse.
  Eigen::Vector2d inverse(const Eigen::Vector2d& p) const;
  /// A gridmap pose in the plan: its heading turned as the local Jacobian turns it.
  Pose2 apply(const Pose2& pose) const;
  /// A plan pose in the gridmap (the inverse of apply).
  Pose2 inverse(const Pose2& pose) const;
  /// d apply / d g at `g` (plan metres per world metre), by central differences over 0.1 m.
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& g) const;
};

/// The warp's scale (world metres per plan metre, as floorplan_scale) over `points` (gridmap
/// metres): the median of the local scales 1 / sqrt(det J), and their spread (a robust standard
/// deviation: 1.4826 times the median absolute deviation, relative to the median). A bent or
/// locally misdrawn plan has no single scale: the spread says how far one global scale may be
/// off at a place.
struct WarpScale {
  double scale = 1.0;         ///< world metres per plan metre, the median
  double relative_std = 0.0;  ///< spread, a share of `scale`
  /// The scale of the least-squares similarity from the points to their images (world metres
  /// per plan metre): the bent map's global scale, as a global fit over the building sees it.
  double similarity_scale = 1.0;
};
WarpScale warp_scale(const MapWarp& warp, const std::vector<Eigen::Vector2d>& points);

/// What align_maps found.
struct MapAlignment {
  /// The global similarity it started from (refined by `faces` when that was fitted).
  MapRegistration registration;
  /// Where the laser meets the drawn walls: the faces' offsets off the strokes, and the
  /// registration they refined.
  WallFaceFit faces;
  /// The plan with its strokes grown to those faces (plan_at_faces), for the run to localize
  /// on; unset when the faces were not fitted or the plan is a vector drawing.
  std::optional<OccupancyGrid> plan_at_faces;
  /// Plan wall surface points and the gridmap wall points matched to them (metres), one per
  /// gridmap wall point within pair_radius of the refined plan walls.
  ReferencePairs pairs;
  /// The bent gridmap's fit (MapFitScorer, on the registration's final wall points): its score
  /// is the fitness.
  MapFit fit;
  /// Another place the gridmap could be: a registration alternative, bent as the best was.
  struct Other {
    MapSimilarity start;  ///< the registration's similarity it was bent from
    MapFit fit;           ///< its bent map's fit
  };
  /// The best-fitting of the registration's alternatives once bent (none when it had none).
  std::optional<Other> runner_up;
  /// The runner-up's fitness over the fitness (0 without a runner-up or below zero, 1 when the
  /// fitness is not positive): near 1, another place fits as well.
  double ambiguity = 0.0;
  MapAlignmentOptions options;  ///< what it ran with and was judged by
  /// The best registration bent onto the plan (unset when nothing was registered).
  std::optional<MapWarp> warp;
  /// Its scale and spread over the gridmap wall points it was bent on.
  WarpScale scale;
  /// fit.score >= min_fitness, fit.on_walls >= min_on_walls, ambiguity < max_ambiguity and at
  /// least 3 pairs
  bool accepted = false;
  std::string diagnosis;           ///< why not accepted (empty when accepted)
  std::size_t points = 0;          ///< gridmap wall points used
  int stages = 0;                  ///< lattice stages run
  double median_distance_m = 0.0;  ///< matched points' distance to the plan walls at the end
  double seconds = 0.0;            ///< wall clock
};

/// The gridmap aligned to the plan from the maps alone: a global registration over scale,
/// rotation and translation (register_maps), then a non-rigid refinement, coarse to fine: each
/// gridmap wall point, mapped by the similarity and a smooth displacement lattice, is matched
/// to the nearest plan wall surface within a shrinking radius (rejected when the walls'
/// directions disagree), and the lattice is refitted to move the points across their walls
/// onto them (point to plane: along a wall only its ends and corners tell). The final matches
/// of the points on a straight gridmap wall are reference pairs for every mapping model (a
/// corner or a clutter blob tells no wall it lies on: with their pairs, fr079's best model
/// was 0.676 m off, without them 0.643 m). The registration's alternatives are bent too.
/// Scores the result as the registration does; not accepted below options.min_fitness or
/// min_on_walls, or at max_ambiguity and above.
MapAlignment align_maps(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                        PlanWalls plan_walls, const MapRegistrationOptions& registration = {},
                        const MapAlignmentOptions& options = {});

}  // namespace floorgrid
