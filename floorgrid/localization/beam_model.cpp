#include "floorgrid/localization/beam_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <system_error>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {
namespace {

// Below this many beams per thread, starting a thread costs more than it saves (a thread start
// is ~20 us, a beam ~0.1-0.3 us).
constexpr std::size_t kMinBeamsPerThread = 2'000;

// Beyond this many standard deviations from both ends of [0, z_max] the Gaussian's mass
// outside the interval is below 1e-15 and its normalization is 1.
constexpr double kNormalizationSigmas = 8.0;

/// The beams' directions in the robot frame and the grid's yaw, as cos and sin, computed once
/// per scan.
struct BeamDirections {
  std::vector<double> cos_a, sin_a;
  double cos_yaw, sin_yaw;
  BeamDirections(const ScanObservation& scan, double yaw)
      : cos_yaw(std::cos(yaw)), sin_yaw(std::sin(yaw)) {
    cos_a.resize(scan.size());
    sin_a.resize(scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k) {
      cos_a[k] = std::cos(static_cast<double>(scan.angle[k]));
      sin_a[k] = std::sin(static_cast<double>(scan.angle[k]));
    }
  }
};

/// Per-thread buffers for one particle's rays.
struct RayScratch {
  std::vector<double> dx, dy, cells;
  explicit RayScratch(std::size_t beams) : dx(beams), dy(beams), cells(beams) {}
};

/// Calls visit(k, z_exp) with the expected range (world metres) of every beam of the scan for
/// a particle at `pose` with `scale`: one cos/sin per particle, the rays cast in cells as one
/// fan from the laser origin.
template <typename Visit>
void cast_beams(const GridRayCaster& caster, const ScanObservation& scan,
                const BeamDirections& directions, const Pose2& pose, double scale, double z_max,
                RayScratch& scratch, const Visit& visit) {
  const GridGeometry& g = caster.geometry();
  const double cy = directions.cos_yaw, sy = directions.sin_yaw;
  const double ct = std::cos(pose.theta), st = std::sin(pose.theta);
  // Laser origin p ∘ (laser_origin / s), then into cell coordinates.
  const double lx = scan.laser_origin.x() / scale, ly = scan.laser_origin.y() / scale;
  const double ox = pose.x + ct * lx - st * ly - g.origin.x;
  const double oy = pose.y + st * lx + ct * ly - g.origin.y;
  const double cell_x = (cy * ox + sy * oy) / g.resolution;
  const double cell_y = (-sy * ox + cy * oy) / g.resolution;
  // The heading in the cell frame, applied to each beam's direction.
  const double a = pose.theta - g.origin.theta;
  const double ca = std::cos(a), sa = std::sin(a);
  const std::size_t beams = scan.size();
  for (std::size_t k = 0; k < beams; ++k) {
    scratch.dx[k] = ca * directions.cos_a[k] - sa * directions.sin_a[k];
    scratch.dy[k] = sa * directions.cos_a[k] + ca * directions.sin_a[k];
  }
  const double cells_per_world_metre = 1.0 / (scale * g.resolution);
  const double max_cells = z_max * cells_per_world_metre;
  caster.cast_fan_in_cells(cell_x, cell_y, scratch.dx.data(), scratch.dy.data(), beams, max_cells,
                           scratch.cells.data());
  for (std::size_t k = 0; k < beams; ++k) {
    const double t = scratch.cells[k];
    visit(k, t >= max_cells ? z_max : t / cells_per_world_metre);
  }
}

}  // namespace

void validate_beam_model_options(const BeamModelOptions& o) {
  const auto weight_ok = [](double w) { return std::isfinite(w) && w >= 0.0; };
  require_option(weight_ok(o.weight_hit), "beam_model", "weight_hit", o.weight_hit,
                 "a finite number >= 0");
  require_option(weight_ok(o.weight_unexpected), "beam_model", "weight_unexpected",
                 o.weight_unexpected, "a finite number >= 0");
  require_option(std::isfinite(o.weight_random) && o.weight_random > 0.0, "beam_model",
                 "weight_random", o.weight_random, "a finite number > 0");
  require_option(weight_ok(o.weight_max), "beam_model", "weight_max", o.weight_max,
                 "a finite number >= 0");
  require_option(std::isfinite(o.sigma_hit) && o.sigma_hit > 0.0, "beam_model", "sigma_hit",
                 o.sigma_hit, "a finite number > 0 (metres)");
  require_option(std::isfinite(o.lambda_unexpected) && o.lambda_unexpected > 0.0, "beam_model",
                 "lambda_unexpected", o.lambda_unexpected, "a finite number > 0 (1/metre)");
  require_option(std::isfinite(o.max_range) && o.max_range >= 0.0, "beam_model", "max_range",
                 o.max_range, "a finite number >= 0 (metres; 0: the scan's)");
  require_option(std::isfinite(o.max_window) && o.max_window > 0.0, "beam_model", "max_window",
                 o.max_window, "a finite number > 0 (metres)");
  require_option(std::isfinite(o.beam_weight) && o.beam_weight > 0.0, "beam_model", "beam_weight",
                 o.beam_weight, "a finite number > 0");
}

BeamModel::BeamModel(const OccupancyGrid& grid, const BeamModelOptions& options)
    : options_(options) {
  validate_beam_model_options(options_);
  if (grid.geometry().size() == 0)
    throw InputError("the map has no cells", {}, 0, "beam_model.map");
  const double total = options_.weight_hit + options_.weight_unexpected + options_.weight_random +
                       options_.weight_max;
  w_hit_ = options_.weight_hit / total;
  w_unexpected_ = options_.weight_unexpected / total;
  w_random_ = options_.weight_random / total;
  w_max_ = options_.weight_max / total;
  caster_ = GridRayCaster(grid, {.unknown_is_occupied = options_.unknown_is_occupied});
}

double BeamModel::max_range_for(const ScanObservation& scan) const {
  const double z_max = options_.max_range > 0.0 ? options_.max_range : scan.max_range;
  if (!(std::isfinite(z_max) && z_max > 0.0)) {
    std::ostringstream message;
    message << "must be set: the scan's max range is not a finite number > 0 (got "
            << scan.max_range << ")";
    throw InputError(message.str(), {}, 0, "beam_model.max_range");
  }
  return z_max;
}

double BeamModel::beam_probability(double z, double z_exp, double z_max) const {
  if (!(z >= 0.0 && z <= z_max))
    return 0.0;
  const double lambda = options_.lambda_unexpected;
  return mixture(z, z_exp, z_max, lambda * std::exp(-lambda * z));
}

double BeamModel::mixture(double z, double z_exp, double z_max, double unexpected_at_z) const {
  const double sigma = options_.sigma_hit;
  // eq. 3.43: the Gaussian about z_exp, normalized over [0, z_max].
  double mass = 1.0;
  if (z_exp < kNormalizationSigmas * sigma || z_max - z_exp < kNormalizationSigmas * sigma) {
    const double k = 1.0 / (sigma * std::numbers::sqrt2);
    mass = 0.5 * (std::erf((z_max - z_exp) * k) + std::erf(z_exp * k));
  }
  const double e = (z - z_exp) / sigma;
  const double p_hit =
      mass > 0.0 ? std::exp(-0.5 * e * e) / (sigma * std::sqrt(2.0 * std::numbers::pi) * mass)
                 : 0.0;
  // eq. 3.46: unexpected obstacles before the wall, normalized over [0, z_exp).
  const double p_unexpected =
      z < z_exp ? unexpected_at_z / -std::expm1(-options_.lambda_unexpected * z_exp) : 0.0;
  // eq. 3.44 and 3.45.
  const double p_random = 1.0 / z_max;
  const double window = std::min(options_.max_window, z_max);
  const double p_max = z >= z_max - window ? 1.0 / window : 0.0;
  return w_hit_ * p_hit + w_unexpected_ * p_unexpected + w_random_ * p_random + w_max_ * p_max;
}

void BeamModel::log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                               std::vector<double>& out, int threads) const {
  const std::size_t n = particles.size();
  out.assign(n, 0.0);
  const std::size_t beams = scan.size();
  if (n == 0 || beams == 0)
    return;
  const double z_max = max_range_for(scan);
  const BeamDirections directions(scan, caster_.geometry().origin.theta);
  // Per beam, what does not depend on the particle: the range (longer ones read as max
  // readings) and the unnormalized unexpected-obstacle density lambda exp(-lambda z).
  const double lambda = options_.lambda_unexpected;
  std::vector<double> ranges(beams), unexpected(beams);
  for (std::size_t k = 0; k < beams; ++k) {
    ranges[k] = std::clamp(static_cast<double>(scan.range[k]), 0.0, z_max);
    unexpected[k] = lambda * std::exp(-lambda * ranges[k]);
  }
  const auto score_block = [&](std::size_t begin, std::size_t end) {
    RayScratch scratch(beams);
    for (std::size_t i = begin; i < end; ++i) {
      double sum = 0.0;
      cast_beams(caster_, scan, directions, particles.pose(i), particles.scale_of(i), z_max,
                 scratch, [&](std::size_t k, double z_exp) {
                   sum += std::log(mixture(ranges[k], z_exp, z_max, unexpected[k]));
                 });
      out[i] = options_.beam_weight * sum;
    }
  };
  parallel_blocks(n, threads_for(n * beams, kMinBeamsPerThread, threads), score_block);
}

double BeamModel::mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                                       double scale) const {
  const std::size_t beams = scan.size();
  if (beams == 0)
    return 0.0;
  const double z_max = max_range_for(scan);
  const double inv_two_sigma2 = 1.0 / (2.0 * options_.sigma_hit * options_.sigma_hit);
  double sum = 0.0;
  RayScratch scratch(beams);
  cast_beams(caster_, scan, BeamDirections(scan, caster_.geometry().origin.theta), pose, scale,
             z_max, scratch, [&](std::size_t k, double z_exp) {
               const double e = std::min(static_cast<double>(scan.range[k]), z_max) - z_exp;
               sum += std::exp(-e * e * inv_two_sigma2);
             });
  return sum / static_cast<double>(beams);
}

std::vector<double> BeamModel::expected_ranges(const ScanObservation& scan, const Pose2& pose,
                                               double scale) const {
  std::vector<double> out(scan.size());
  if (scan.size() == 0)
    return out;
  const double z_max = max_range_for(scan);
  RayScratch scratch(scan.size());
  cast_beams(caster_, scan, BeamDirections(scan, caster_.geometry().origin.theta), pose, scale,
             z_max, scratch, [&](std::size_t k, double z_exp) { out[k] = z_exp; });
  return out;
}

}  // namespace floorgrid
