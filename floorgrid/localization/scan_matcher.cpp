#include "floorgrid/localization/scan_matcher.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

void validate(const ScanMatchOptions& o) {
  const auto positive = [](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError("must be > 0", {}, 0, std::string("scan_match.") + field);
  };
  if (o.max_iterations < 1)
    throw InputError("must be >= 1", {}, 0, "scan_match.max_iterations");
  positive(o.max_correspondence, "max_correspondence");
  positive(o.min_correspondence, "min_correspondence");
  if (o.min_correspondence > o.max_correspondence)
    throw InputError("must be <= max_correspondence", {}, 0, "scan_match.min_correspondence");
  positive(o.robust_scale, "robust_scale");
  positive(o.inlier_distance, "inlier_distance");
  if (o.min_inliers < 1)
    throw InputError("must be >= 1", {}, 0, "scan_match.min_inliers");
  if (!(o.min_inlier_fraction >= 0.0 && o.min_inlier_fraction <= 1.0))
    throw InputError("must be in [0, 1]", {}, 0, "scan_match.min_inlier_fraction");
  if (!(o.min_constraint >= 0.0 && o.min_constraint <= 0.5))
    throw InputError("must be in [0, 0.5]", {}, 0, "scan_match.min_constraint");
  positive(o.max_correction, "max_correction");
  positive(o.max_heading_correction, "max_heading_correction");
  positive(o.tolerance, "tolerance");
}

std::string_view to_string(ScanMatchFailure failure) {
  switch (failure) {
    case ScanMatchFailure::none:
      return "none";
    case ScanMatchFailure::too_few_inliers:
      return "too_few_inliers";
    case ScanMatchFailure::degenerate:
      return "degenerate";
    case ScanMatchFailure::too_far:
      return "too_far";
  }
  return "unknown";
}

namespace {

/// One scan's normal equations at a pose, for the pose parameters (x, y, theta) and two
/// parameters shared by every scan, g = (u, shift): the inverse scale u = 1 / scale and the
/// shift of the walls' surfaces towards the laser (map metres):
/// [A C; C^T D] [dpose; dg] = -[b; e].
struct Linearization {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 2> C = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::Matrix2d D = Eigen::Matrix2d::Zero();
  Eigen::Vector2d e = Eigen::Vector2d::Zero();
  std::size_t inliers = 0;
  double inlier_square_sum = 0.0;
  Eigen::Matrix2d normals = Eigen::Matrix2d::Zero();  // sum over inliers of n n^T (or I / 2)

  /// The weakest translation direction's share of the inliers' normals, and the direction.
  std::pair<double, Eigen::Vector2d> constraint() const {
    if (inliers == 0)
      return {0.0, Eigen::Vector2d::UnitX()};
    const Eigen::Matrix2d m = normals / static_cast<double>(inliers);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(m);
    return {eigen.eigenvalues()(0), eigen.eigenvectors().col(0)};
  }
};

/// Geman-McClure IRLS weight.
double robust_weight(double r, double c) {
  const double k = c * c / (c * c + r * r);
  return k * k;
}

/// Adds one residual r with weight w: its Jacobian j on the pose and jg on (u, shift).
void add_row(Linearization& l, const Eigen::Vector3d& j, const Eigen::Vector2d& jg, double r,
             double w) {
  l.A.noalias() += w * j * j.transpose();
  l.b += w * r * j;
  l.C.noalias() += w * j * jg.transpose();
  l.D.noalias() += w * jg * jg.transpose();
  l.e += w * r * jg;
}

/// `shift`: map metres by which the walls' surfaces lie nearer the laser than the field says;
/// `model_shift`: every wall row depends on it (posts and corners as circles of radius
/// surface_offset() + shift), as the joint fit with a surface shift needs.
Linearization linearize(const WallField& walls, const ScanObservation& scan, const Pose2& pose,
                        double u, double gate, const ScanMatchOptions& options, double shift = 0.0,
                        bool model_shift = false) {
  Linearization l;
  const Eigen::Matrix2d R = pose.rotation();
  const Eigen::Vector2d t = pose.translation();
  const Eigen::Vector2d laser = t + u * (R * scan.laser_origin);
  for (std::size_t j = 0; j < scan.size(); ++j) {
    const Eigen::Vector2d v = R * Eigen::Vector2d(scan.end_x[j], scan.end_y[j]);
    const Eigen::Vector2d p = t + u * v;
    const WallPoint* wall = walls.nearest(p);
    if (!wall)
      continue;
    const Eigen::Vector2d err = p - wall->point.cast<double>();
    const double distance = err.norm();
    if (distance > gate)
      continue;
    const Eigen::Vector2d n = wall->normal.cast<double>();
    // A one-sided wall (a face of a wall drawn as two lines) is seen from its room side only.
    if (wall->one_sided && (laser - wall->point.cast<double>()).dot(n) <= 0.0)
      continue;
    const Eigen::Vector2d dp_dtheta(-u * v.y(), u * v.x());
    const bool line = n.squaredNorm() > 0.5;
    if (line || ((walls.surface_offset() > 0.0 || model_shift) && distance > 0.0)) {
      // Point to line: the wall's line, or for a post or corner whose surface lies
      // surface_offset() off its point, that circle's tangent facing the endpoint. The shift
      // moves the surface towards the laser: the residual falls by it on the laser's side.
      const Eigen::Vector2d d = line ? n : Eigen::Vector2d(err / distance);
      // The side only matters to the shift's row; the matcher's own rows skip the test.
      const double side =
          !model_shift || !line || (laser - wall->point.cast<double>()).dot(n) >= 0.0 ? 1.0 : -1.0;
      const double r =
          (line ? walls.surface_residual(*wall, p, laser) : distance - walls.surface_offset()) -
          side * shift;
      add_row(l, {d.x(), d.y(), d.dot(dp_dtheta)}, {d.dot(v), -side}, r,
              robust_weight(r, options.robust_scale));
      if (std::abs(r) < options.inlier_distance) {
        ++l.inliers;
        l.inlier_square_sum += r * r;
        if (line)
          l.normals.noalias() += n * n.transpose();
        else
          l.normals += 0.5 * Eigen::Matrix2d::Identity();
      }
    } else {
      const double w = robust_weight(distance, options.robust_scale);
      add_row(l, {1.0, 0.0, dp_dtheta.x()}, {v.x(), 0.0}, err.x(), w);
      add_row(l, {0.0, 1.0, dp_dtheta.y()}, {v.y(), 0.0}, err.y(), w);
      if (distance < options.inlier_distance) {
        ++l.inliers;
        l.inlier_square_sum += distance * distance;
        l.normals += 0.5 * Eigen::Matrix2d::Identity();
      }
    }
  }
  return l;
}

/// Solves (A + damping) x = rhs; damping keeps unconstrained directions (a corridor's length)
/// from moving instead of failing.
Eigen::Vector3d solve_damped(const Eigen::Matrix3d& A, const Eigen::Vector3d& rhs) {
  const double damping = 1e-6 * std::max(A.trace(), 1e-9);
  const Eigen::Matrix3d M = A + damping * Eigen::Matrix3d::Identity();
  return M.ldlt().solve(rhs);
}

/// The gate of iteration k: max_correspondence shrinking by 0.7 per iteration to the minimum.
double gate_at(int k, const ScanMatchOptions& options) {
  return std::max(options.min_correspondence, options.max_correspondence * std::pow(0.7, k));
}

Pose2 moved(const Pose2& pose, const Eigen::Vector3d& step) {
  return {pose.x + step.x(), pose.y + step.y(), normalize_angle(pose.theta + step.z())};
}

}  // namespace

ScanMatch match_scan(const WallField& walls, const ScanObservation& scan, const Pose2& initial,
                     double scale, const ScanMatchOptions& options) {
  validate(options);
  if (!(scale > 0.0))
    throw InputError("must be > 0", {}, 0, "scan_match.scale");
  ScanMatch m;
  m.pose = initial;
  m.endpoints = scan.size();
  const double u = 1.0 / scale;
  for (int k = 0; k < options.max_iterations; ++k) {
    const double gate = gate_at(k, options);
    const Linearization l = linearize(walls, scan, m.pose, u, gate, options);
    m.iterations = k + 1;
    if (l.A.trace() <= 0.0)
      break;
    const Eigen::Vector3d step = solve_damped(l.A, -l.b);
    m.pose = moved(m.pose, step);
    if (gate <= options.min_correspondence && step.head<2>().norm() < options.tolerance &&
        std::abs(step.z()) < options.tolerance)
      break;
  }
  const Linearization l = linearize(walls, scan, m.pose, u, options.min_correspondence, options);
  m.inliers = l.inliers;
  m.rms = l.inliers ? std::sqrt(l.inlier_square_sum / static_cast<double>(l.inliers)) : 0.0;
  std::tie(m.constraint, m.weak_direction) = l.constraint();
  const double fraction =
      m.endpoints ? static_cast<double>(m.inliers) / static_cast<double>(m.endpoints) : 0.0;
  if (m.inliers < options.min_inliers || fraction < options.min_inlier_fraction) {
    m.failure = ScanMatchFailure::too_few_inliers;
  } else if (m.constraint < options.min_constraint) {
    m.failure = ScanMatchFailure::degenerate;
  } else if ((m.pose.translation() - initial.translation()).norm() > options.max_correction ||
             std::abs(normalize_angle(m.pose.theta - initial.theta)) >
                 options.max_heading_correction) {
    m.failure = ScanMatchFailure::too_far;
  }
  return m;
}

ScanObservation beam_consistent(const ScanObservation& scan, const GridRayCaster& walls,
                                const Pose2& pose, double scale, double tolerance) {
  ScanObservation kept;
  kept.max_range = scan.max_range;
  kept.laser_origin = scan.laser_origin;
  kept.no_returns = scan.no_returns;
  const Eigen::Vector2d origin = pose.transform(scan.laser_origin / scale);
  const double max_range = scan.max_range / scale + 2.0 * tolerance;
  for (std::size_t j = 0; j < scan.size(); ++j) {
    const double range = scan.range[j] / scale;
    const double expected = walls.cast(origin, pose.theta + scan.angle[j], max_range);
    if (std::abs(range - expected) > tolerance)
      continue;
    kept.push_back_beam(scan, j);
  }
  return kept;
}

ScanMatch match_scan(const WallField& walls, const ScanObservation& scan, const Pose2& initial,
                     double scale, const ScanMatchOptions& options, const GridRayCaster& caster,
                     double tolerance) {
  const ScanObservation kept = beam_consistent(scan, caster, initial, scale, tolerance);
  ScanMatch m = match_scan(walls, kept, initial, scale, options);
  // Judged against the whole scan: a pose that explains few beams is not a good match however
  // well those few fit.
  m.endpoints = scan.size();
  if (m.failure != ScanMatchFailure::too_few_inliers &&
      static_cast<double>(m.inliers) <
          options.min_inlier_fraction * static_cast<double>(scan.size()))
    m.failure = ScanMatchFailure::too_few_inliers;
  return m;
}

ScaleProfile profile_scale(const WallField& walls, std::span<const ScanObservation* const> scans,
                           std::span<const Pose2> poses, const std::vector<double>& candidates,
                           const ScanMatchOptions& options, const GridRayCaster* caster,
                           double tolerance) {
  validate(options);
  if (scans.size() != poses.size())
    throw InputError("needs one pose per scan", {}, 0, "scale_profile.poses");
  ScaleProfile profile;
  profile.scales = candidates;
  std::size_t most = 0;
  for (const double scale : candidates) {
    if (!(scale > 0.0))
      throw InputError("candidate scales must be > 0", {}, 0, "scale_profile.candidates");
    std::size_t inliers = 0;
    for (std::size_t i = 0; i < scans.size(); ++i) {
      const ScanMatch m =
          caster ? match_scan(walls, *scans[i], poses[i], scale, options, *caster, tolerance)
                 : match_scan(walls, *scans[i], poses[i], scale, options);
      inliers += m.inliers;
    }
    profile.inliers.push_back(inliers);
    if (inliers > most) {
      most = inliers;
      profile.best = scale;
    }
  }
  return profile;
}

ScaleFit fit_scale(const WallField& walls, std::span<const ScanObservation* const> scans,
                   std::span<const Pose2> poses, double initial_scale,
                   const ScanMatchOptions& options, int max_iterations, int jackknife_blocks,
                   bool fit_shift) {
  validate(options);
  if (scans.size() != poses.size() || scans.empty())
    throw InputError("needs as many poses as scans, at least one", {}, 0, "scale_fit.scans");
  if (!(initial_scale > 0.0))
    throw InputError("must be > 0", {}, 0, "scale_fit.initial_scale");
  ScaleFit fit;
  // Each pose first matched alone at the initial scale (coarse to fine); the scans that do not
  // match at all (too few inliers, or a pose that had to move far) stay out of the fit.
  std::vector<std::size_t> used;
  fit.poses.assign(poses.begin(), poses.end());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const ScanMatch m = match_scan(walls, *scans[i], poses[i], initial_scale, options);
    fit.poses[i] = m.pose;
    if (m.failure == ScanMatchFailure::none || m.failure == ScanMatchFailure::degenerate)
      used.push_back(i);
  }
  // The shared parameters g = (u, shift); without fit_shift only u moves (the shift stays 0).
  Eigen::Vector2d g(1.0 / initial_scale, 0.0);
  fit.scans = used.size();
  if (used.empty()) {
    fit.scale = initial_scale;
    return fit;
  }
  std::vector<Linearization> lin(used.size());
  std::vector<Eigen::LDLT<Eigen::Matrix3d>> solvers(used.size());
  const auto linearize_all = [&] {
    for (std::size_t k = 0; k < used.size(); ++k) {
      lin[k] = linearize(walls, *scans[used[k]], fit.poses[used[k]], g(0),
                         options.min_correspondence, options, g(1), fit_shift);
      const double damping = 1e-6 * std::max(lin[k].A.trace(), 1e-9);
      solvers[k].compute(lin[k].A + damping * Eigen::Matrix3d::Identity());
    }
  };
  // Schur complement on g: (sum D - C^T A^-1 C) dg = -(sum e - C^T A^-1 b), per scan.
  const auto reduced = [&](std::size_t k, Eigen::Matrix2d& S, Eigen::Vector2d& G) {
    S = lin[k].D - lin[k].C.transpose() * solvers[k].solve(lin[k].C);
    G = lin[k].e - lin[k].C.transpose() * solvers[k].solve(lin[k].b);
  };
  // The step of g from the summed system: u alone, or u and the shift.
  const auto solve_shared = [&](const Eigen::Matrix2d& S, const Eigen::Vector2d& G) {
    Eigen::Vector2d dg = Eigen::Vector2d::Zero();
    if (!fit_shift) {
      dg(0) = S(0, 0) > 0.0 ? -G(0) / S(0, 0) : 0.0;
    } else if (S.determinant() > 0.0 && S(0, 0) > 0.0) {
      dg = -S.ldlt().solve(G);
    }
    return dg;
  };
  for (int it = 0; it < max_iterations; ++it) {
    linearize_all();
    Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
    Eigen::Vector2d G = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < used.size(); ++k) {
      Eigen::Matrix2d s;
      Eigen::Vector2d gk;
      reduced(k, s, gk);
      S += s;
      G += gk;
    }
    const Eigen::Vector2d dg = solve_shared(S, G);
    double largest = dg.cwiseAbs().maxCoeff();
    for (std::size_t k = 0; k < used.size(); ++k) {
      const Eigen::Vector3d step = -solvers[k].solve(lin[k].b + lin[k].C * dg);
      fit.poses[used[k]] = moved(fit.poses[used[k]], step);
      largest = std::max(largest, step.cwiseAbs().maxCoeff());
    }
    g += dg;
    fit.iterations = it + 1;
    if (largest < options.tolerance)
      break;
  }
  // Jackknife at the solution: leaving block B out moves g by -(S - S_B)^-1 (G - G_B).
  linearize_all();
  std::vector<Eigen::Matrix2d> s_of(used.size());
  std::vector<Eigen::Vector2d> g_of(used.size());
  Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
  Eigen::Vector2d G = Eigen::Vector2d::Zero();
  fit.residuals = 0;
  for (std::size_t k = 0; k < used.size(); ++k) {
    reduced(k, s_of[k], g_of[k]);
    S += s_of[k];
    G += g_of[k];
    fit.residuals += lin[k].inliers;
  }
  const int blocks = std::clamp<int>(jackknife_blocks, 2, static_cast<int>(used.size()));
  std::vector<Eigen::Vector2d> estimates;
  if (used.size() >= 2 && S(0, 0) > 0.0) {
    for (int b = 0; b < blocks; ++b) {
      const std::size_t from = used.size() * b / blocks, to = used.size() * (b + 1) / blocks;
      Eigen::Matrix2d sb = Eigen::Matrix2d::Zero();
      Eigen::Vector2d gb = Eigen::Vector2d::Zero();
      for (std::size_t k = from; k < to; ++k) {
        sb += s_of[k];
        gb += g_of[k];
      }
      if (S(0, 0) - sb(0, 0) > 0.0)
        estimates.push_back(g + solve_shared(S - sb, G - gb));
    }
  }
  Eigen::Vector2d std_g = Eigen::Vector2d::Zero();
  if (estimates.size() >= 2) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& e : estimates)
      mean += e;
    mean /= static_cast<double>(estimates.size());
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& e : estimates)
      sum += (e - mean).cwiseAbs2();
    const double k = static_cast<double>(estimates.size());
    std_g = ((k - 1.0) / k * sum).cwiseSqrt();
  }
  fit.scale = 1.0 / g(0);
  fit.scale_std = std_g(0) / (g(0) * g(0));
  fit.surface_shift = g(1);
  fit.surface_shift_std = std_g(1);
  return fit;
}

}  // namespace floorgrid
