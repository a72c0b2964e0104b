#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/localization/particles.hpp"

namespace floorgrid {

/// A particle set summarized: its mean pose (thesis eq. 4.24-4.26), its spread and how many
/// particles effectively carry the weight. Positions are in the map's frame and metres (a map
/// metre is `scale` world metres).
struct PoseEstimate {
  /// Weighted mean position (eq. 4.24, 4.25) and circular mean heading
  /// atan2(sum w sin theta, sum w cos theta) (eq. 4.26), map frame.
  Pose2 pose;
  double scale = 1.0;  ///< weighted mean scale, world metres per map metre (1 without scale)
  /// Weighted covariance of the positions, map metres squared.
  Eigen::Matrix2d position_covariance = Eigen::Matrix2d::Zero();
  /// Map metres: the square root of the LARGEST eigenvalue of position_covariance, i.e. the
  /// standard deviation along the worst direction (a cloud stretched along a corridor is not
  /// localized along it, whatever its width). For an isotropic cloud it is the per-axis sigma.
  double position_std = 0.0;
  /// Radians: circular standard deviation sqrt(-2 ln R), R = |sum w e^(i theta)| the mean
  /// resultant length; equals sigma for a wrapped normal. Capped at sqrt(-2 ln 1e-300) ~ 37
  /// (R = 0: headings spread evenly); anything above ~2 means "no heading".
  double heading_std = 0.0;
  double scale_std = 0.0;  ///< weighted standard deviation of the scale (0 without scale)
  /// N_eff = (sum w)^2 / sum w^2 (1 / sum w^2 for normalized weights).
  double effective_sample_size = 0.0;
  double ess_ratio = 0.0;     ///< N_eff / N, in (0, 1]
  std::size_t particles = 0;  ///< N
};

/// N_eff = (sum w)^2 / sum w^2 of any non-negative weights (1 / sum w^2 once normalized);
/// 0 when they sum to 0.
double effective_sample_size(std::span<const double> weights);

/// The weighted circular mean atan2(sum w sin a, sum w cos a) (eq. 4.26), in (-pi, pi];
/// `weights` empty means equal weights. 0 when the resultant vanishes.
double circular_mean(std::span<const double> angles, std::span<const double> weights = {});

/// Summarizes `particles` (their weights, or equal weights when the set has none); two O(N)
/// passes (mean, then covariance about it). An empty set gives the default estimate.
PoseEstimate estimate_pose(const ParticleSet& particles);

}  // namespace floorgrid
