#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/localization/ray_marching.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/localization/wall_field.hpp"

namespace floorgrid {

/// How a scan is matched onto a map's walls (a robust point-to-line ICP on a WallField).
struct ScanMatchOptions {
  int max_iterations = 20;  ///< Gauss-Newton iterations at most (>= 1)
  /// Map metres: correspondences farther than this are ignored; the gate shrinks
  /// geometrically to min_correspondence over the first iterations (coarse to fine).
  double max_correspondence = 0.5;
  double min_correspondence = 0.2;  ///< map metres (> 0, <= max_correspondence)
  /// Map metres: scale of the Geman-McClure weight (c^2 / (c^2 + r^2))^2: residuals well above
  /// it (furniture in front of a wall, a misdrawn wall) barely pull.
  double robust_scale = 0.05;
  double inlier_distance = 0.08;  ///< map metres: a residual this small is an inlier
  /// Accept a match only with at least this many inliers (>= 1) ...
  std::size_t min_inliers = 20;
  /// ... making at least this share of the scan's endpoints, in [0, 1].
  double min_inlier_fraction = 0.3;
  /// The weakest direction of translation must be constrained by at least this share of the
  /// inliers' wall normals (the smaller eigenvalue of their mean n n^T, in [0, 0.5]): a scan
  /// that sees only the two walls of a corridor cannot place the robot along it.
  double min_constraint = 0.06;
  double max_correction = 0.5;           ///< map metres: a match moving the pose farther fails
  double max_heading_correction = 0.15;  ///< radians: likewise for the heading
  double tolerance = 1e-5;  ///< stop when a step moves less than this (metres, radians)
};

/// Throws InputError naming `scan_match.<field>` when an option is out of range.
void validate(const ScanMatchOptions& options);

/// Why a match was not accepted.
enum class ScanMatchFailure {
  none,             ///< accepted
  too_few_inliers,  ///< fewer than min_inliers / min_inlier_fraction
  degenerate,       ///< a direction of translation is unconstrained (min_constraint)
  too_far,          ///< the pose moved beyond max_correction / max_heading_correction
};

/// "none", "too_few_inliers", "degenerate" or "too_far".
std::string_view to_string(ScanMatchFailure failure);

/// A scan matched onto a map.
struct ScanMatch {
  ScanMatchFailure failure = ScanMatchFailure::none;  ///< why not accepted (none: ok)
  Pose2 pose;                 ///< the refined pose (map frame), even when not accepted
  std::size_t endpoints = 0;  ///< endpoints of the scan
  std::size_t inliers = 0;    ///< endpoints within inlier_distance of a wall at `pose`
  double rms = 0.0;           ///< map metres: root mean square residual of the inliers
  double constraint = 0.0;    ///< the weakest translation direction's share (min_constraint)
  /// Unit vector (map frame) of the weakest translation direction: along a corridor.
  Eigen::Vector2d weak_direction = Eigen::Vector2d::UnitX();
  int iterations = 0;  ///< Gauss-Newton iterations run
  /// Whether the match was accepted.
  bool ok() const { return failure == ScanMatchFailure::none; }
};

/// Refines `initial` (the robot's pose in the map) so that the scan's endpoints, scaled from
/// world metres into map metres by 1 / `scale` (world metres per map metre), lie on the walls:
/// robust Gauss-Newton on point-to-line residuals (point-to-point where a wall has no normal),
/// correspondences re-found each iteration in O(1) from the WallField. Then judges the match.
ScanMatch match_scan(const WallField& walls, const ScanObservation& scan, const Pose2& initial,
                     double scale, const ScanMatchOptions& options = {});

/// The beams of `scan` whose range, seen from `pose` (map frame; ranges divided by `scale`),
/// reaches the first wall along the beam in `walls` within `tolerance` map metres: endpoints
/// on furniture the map lacks (short) and beams through walls drawn where there are none
/// (long) are left out. For matching a scan onto a plan, whose walls are all the laser should
/// be matched to.
ScanObservation beam_consistent(const ScanObservation& scan, const GridRayCaster& walls,
                                const Pose2& pose, double scale, double tolerance);

/// match_scan on the beams of `scan` that are consistent with `walls` at `initial`
/// (beam_consistent with `tolerance`); the inlier share is still of all the scan's endpoints.
ScanMatch match_scan(const WallField& walls, const ScanObservation& scan, const Pose2& initial,
                     double scale, const ScanMatchOptions& options, const GridRayCaster& caster,
                     double tolerance);

/// How well each candidate scale lets scans land on the walls.
struct ScaleProfile {
  double best = 1.0;                 ///< the candidate with the most inliers
  std::vector<double> scales;        ///< the candidates
  std::vector<std::size_t> inliers;  ///< inliers summed over the scans, per candidate
};

/// For each candidate scale, every scan is matched from its pose (match_scan; with `caster`,
/// by its beams consistent with it) and its inliers counted: the scale at which the most
/// endpoints lie on the walls wins. Inliers are a tight count (inlier_distance), so endpoints
/// on furniture or on walls drawn elsewhere count for no scale, unlike in a likelihood,
/// where a stretched scan pulls furniture endpoints onto the walls behind them.
ScaleProfile profile_scale(const WallField& walls, std::span<const ScanObservation* const> scans,
                           std::span<const Pose2> poses, const std::vector<double>& candidates,
                           const ScanMatchOptions& options = {},
                           const GridRayCaster* caster = nullptr, double tolerance = 0.5);

/// A plan's scale fitted jointly with the poses of many scans.
struct ScaleFit {
  double scale = 1.0;         ///< world metres per map metre
  double scale_std = 0.0;     ///< its standard deviation (delete-a-block jackknife)
  std::vector<Pose2> poses;   ///< the refined pose of every scan given
  std::size_t scans = 0;      ///< scans that constrained the fit
  std::size_t residuals = 0;  ///< inlier residuals of the final iteration
  int iterations = 0;         ///< Gauss-Newton iterations run
  /// Map metres by which the walls' surfaces lie nearer the laser than the wall field says
  /// (fitted only with `fit_shift`, else 0): walls built thicker than drawn, or drawn as
  /// single lines where the laser meets faces.
  double surface_shift = 0.0;
  double surface_shift_std = 0.0;  ///< its standard deviation (the same jackknife)
};

/// Fits one scale shared by all `scans` together with each scan's pose (starting from `poses`
/// and `initial_scale`): robust Gauss-Newton on the same residuals as match_scan, with the
/// poses eliminated by a Schur complement (O(scans) per iteration). The scale's uncertainty is
/// a delete-a-block jackknife over `jackknife_blocks` consecutive runs of scans, so errors
/// shared by neighbouring scans (one misdrawn wall) are not counted as independent.
/// `scans` and `poses` have the same length (>= 1). To fit on the beams consistent with a
/// plan (not the endpoints on furniture it lacks), reduce each scan with beam_consistent first.
/// With `fit_shift`, one more parameter is fitted with the scale: a shift of every wall's
/// surface towards the laser that sees it (ScaleFit::surface_shift). A scan sees walls at
/// every range, so a shift (the same at every range) and a scale (proportional to the range)
/// are told apart; fitted with the scale alone, faces that lie in front of the drawn walls
/// shrink every room and bias the scale low.
ScaleFit fit_scale(const WallField& walls, std::span<const ScanObservation* const> scans,
                   std::span<const Pose2> poses, double initial_scale,
                   const ScanMatchOptions& options = {}, int max_iterations = 30,
                   int jackknife_blocks = 20, bool fit_shift = false);

}  // namespace floorgrid
