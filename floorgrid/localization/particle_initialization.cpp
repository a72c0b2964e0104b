#include "floorgrid/localization/particle_initialization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/maps/distance_field.hpp"

namespace floorgrid {
namespace {

// Scales are kept above this (a scale is a ratio of lengths).
constexpr double kMinScale = 1e-6;

void prepare_set(ParticleSet& set, std::size_t count, bool with_scale) {
  set.x.resize(count);
  set.y.resize(count);
  set.theta.resize(count);
  set.scale.assign(with_scale ? count : 0, 1.0);
  set.weight.assign(count, count > 0 ? 1.0 / static_cast<double>(count) : 0.0);
}

double uniform_scale(const std::optional<ScaleRange>& scales, Random& random) {
  if (!scales)
    return 1.0;
  return scales->max > scales->min ? random.uniform(scales->min, scales->max) : scales->min;
}

// A pose hypothesis of the lattice: its score and its index (position, heading, scale).
struct ScoredHypothesis {
  double score;
  std::uint64_t id;
};

// Higher score first; ties broken by the lower index, so the kept set never depends on the
// order of evaluation.
bool better(const ScoredHypothesis& a, const ScoredHypothesis& b) {
  return a.score > b.score || (a.score == b.score && a.id < b.id);
}

// Lattice positions (metres) over the candidate cells, `step` metres apart along the grid axes.
std::vector<Eigen::Vector2d> lattice_positions(const FreeSpaceSampler& free_space, double step) {
  const GridGeometry& g = free_space.geometry();
  const double step_cells = step / g.resolution;
  std::vector<Eigen::Vector2d> positions;
  for (double cy = 0.5 * step_cells; cy < g.height; cy += step_cells) {
    for (double cx = 0.5 * step_cells; cx < g.width; cx += step_cells) {
      if (free_space.is_candidate(static_cast<int>(cx), static_cast<int>(cy)))
        positions.push_back(g.from_cell_coordinates({cx, cy}));
    }
  }
  return positions;
}

}  // namespace

void validate(const ScaleRange& r) {
  require_option(std::isfinite(r.min) && r.min > 0.0, "scale_range", "min", r.min, "> 0");
  require_option(std::isfinite(r.max) && r.max >= r.min, "scale_range", "max", r.max, ">= min");
}

void validate(const TrackingStart& s) {
  const char* p = "tracking_start";
  require_option(std::isfinite(s.pose.x) && std::isfinite(s.pose.y) && std::isfinite(s.pose.theta),
                 p, "pose", s.pose.x, "finite");
  require_option(s.position_sigma >= 0.0 && std::isfinite(s.position_sigma), p, "position_sigma",
                 s.position_sigma, ">= 0 metres");
  require_option(s.heading_sigma >= 0.0 && std::isfinite(s.heading_sigma), p, "heading_sigma",
                 s.heading_sigma, ">= 0 radians");
  if (s.scale)
    require_option(*s.scale > 0.0 && std::isfinite(*s.scale), p, "scale", *s.scale, "> 0");
  require_option(s.scale_sigma >= 0.0 && std::isfinite(s.scale_sigma), p, "scale_sigma",
                 s.scale_sigma, ">= 0");
}

void validate(const FreeSpaceOptions& o) {
  require_option(o.max_wall_distance >= 0.0 && std::isfinite(o.max_wall_distance), "free_space",
                 "max_wall_distance", o.max_wall_distance, ">= 0 metres");
}

void validate(const HypothesisSeedingOptions& o) {
  const char* p = "seeding";
  require_option(o.position_step > 0.0 && std::isfinite(o.position_step), p, "position_step",
                 o.position_step, "> 0 metres");
  require_option(o.headings >= 1, p, "headings", o.headings, ">= 1");
  require_option(o.scales >= 1, p, "scales", o.scales, ">= 1");
  require_option(o.keep >= 1, p, "keep", o.keep, ">= 1");
  require_option(o.max_hypotheses >= 1, p, "max_hypotheses", o.max_hypotheses, ">= 1");
  require_option(o.batch >= 1, p, "batch", o.batch, ">= 1");
}

FreeSpaceSampler::FreeSpaceSampler(const OccupancyGrid& grid, const FreeSpaceOptions& options)
    : geometry_(grid.geometry()), mask_(grid.geometry().size(), 0) {
  validate(options);
  DistanceField walls;
  const bool near_walls_only = options.max_wall_distance > 0.0;
  if (near_walls_only)  // capped just above the limit: farther cells read the cap
    walls = occupied_distance_field(grid, options.max_wall_distance + grid.resolution());
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      if (grid.state(ix, iy) != CellState::free)
        continue;
      if (near_walls_only && !(walls.at(ix, iy) <= options.max_wall_distance))
        continue;
      const std::size_t i = grid.index(ix, iy);
      mask_[i] = 1;
      cells_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (cells_.empty())
    throw InputError(near_walls_only ? "no free cell within max_wall_distance of an occupied cell"
                                     : "the map has no free cell: nowhere to localize",
                     {}, 0, "free_space");
}

double FreeSpaceSampler::area() const {
  return static_cast<double>(cells_.size()) * geometry_.resolution * geometry_.resolution;
}

Eigen::Vector2d FreeSpaceSampler::sample_position(Random& random) const {
  const std::uint32_t cell = cells_[static_cast<std::size_t>(
      random.integer(0, static_cast<std::int64_t>(cells_.size()) - 1))];
  const int ix = static_cast<int>(cell % static_cast<std::uint32_t>(geometry_.width));
  const int iy = static_cast<int>(cell / static_cast<std::uint32_t>(geometry_.width));
  const double u = random.uniform(), v = random.uniform();
  return geometry_.from_cell_coordinates({ix + u, iy + v});
}

ParticleSet sample_tracking_start(const TrackingStart& start, std::size_t count, Random& random) {
  validate(start);
  ParticleSet set;
  prepare_set(set, count, start.scale.has_value());
  for (std::size_t i = 0; i < count; ++i) {
    set.x[i] = start.pose.x + random.normal(start.position_sigma);
    set.y[i] = start.pose.y + random.normal(start.position_sigma);
    set.theta[i] = normalize_angle(start.pose.theta + random.normal(start.heading_sigma));
    if (start.scale)
      set.scale[i] = std::max(kMinScale, *start.scale + random.normal(start.scale_sigma));
  }
  return set;
}

void sample_free_space_particles(const FreeSpaceSampler& free_space,
                                 const std::optional<ScaleRange>& scales, Random& random,
                                 ParticleSet& set, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const Eigen::Vector2d p = free_space.sample_position(random);
    set.x[i] = p.x();
    set.y[i] = p.y();
    set.theta[i] = random.uniform(-std::numbers::pi, std::numbers::pi);
    if (set.has_scale())
      set.scale[i] = uniform_scale(scales, random);
  }
}

ParticleSet sample_global(const FreeSpaceSampler& free_space, std::size_t count,
                          const std::optional<ScaleRange>& scales, Random& random) {
  if (scales)
    validate(*scales);
  ParticleSet set;
  prepare_set(set, count, scales.has_value());
  sample_free_space_particles(free_space, scales, random, set, 0, count);
  return set;
}

void sample_disc_particles(const Pose2& center, double radius, double heading_spread, double scale,
                           double scale_sigma, Random& random, ParticleSet& set, std::size_t begin,
                           std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    // Uniform over the disc: the radius goes with the square root of a uniform draw.
    const double r = radius * std::sqrt(random.uniform());
    const double a = random.uniform(-std::numbers::pi, std::numbers::pi);
    set.x[i] = center.x + r * std::cos(a);
    set.y[i] = center.y + r * std::sin(a);
    set.theta[i] = normalize_angle(center.theta + random.uniform(-heading_spread, heading_spread));
    if (set.has_scale())
      set.scale[i] = std::max(kMinScale, scale + random.normal(scale_sigma));
  }
}

HypothesisSeeding seed_best_hypotheses(const FreeSpaceSampler& free_space,
                                       const ScanObservation& scan, const ObservationModel& model,
                                       const HypothesisSeedingOptions& options,
                                       const std::optional<ScaleRange>& scale_range, Random& random,
                                       int threads) {
  validate(options);
  if (scale_range)
    validate(*scale_range);
  HypothesisSeeding result;

  // The lattice: positions x headings x scales, coarsened until it fits max_hypotheses.
  const std::size_t headings = static_cast<std::size_t>(options.headings);
  const std::size_t scales = scale_range ? static_cast<std::size_t>(options.scales) : 1;
  double step = options.position_step;
  std::vector<Eigen::Vector2d> positions = lattice_positions(free_space, step);
  while (positions.size() * headings * scales > options.max_hypotheses && positions.size() > 1) {
    const double excess = static_cast<double>(positions.size() * headings * scales) /
                          static_cast<double>(options.max_hypotheses);
    step *= std::max(1.01, 1.01 * std::sqrt(excess));
    positions = lattice_positions(free_space, step);
  }
  if (positions.empty())  // a free space thinner than the lattice: one sampled position
    positions.push_back(free_space.sample_position(random));
  const double heading_step = 2.0 * std::numbers::pi / static_cast<double>(headings);
  const double scale_step =
      scale_range ? (scale_range->max - scale_range->min) / static_cast<double>(scales) : 0.0;
  auto heading_of = [&](std::size_t h) {
    return -std::numbers::pi + (static_cast<double>(h) + 0.5) * heading_step;
  };
  auto scale_of = [&](std::size_t k) {
    return scale_range ? scale_range->min + (static_cast<double>(k) + 0.5) * scale_step : 1.0;
  };
  const std::size_t total = positions.size() * headings * scales;
  const std::size_t keep = std::min(options.keep, total);

  // Score in batches; whenever 2K candidates are held, keep the best K (linear time).
  std::vector<ScoredHypothesis> best;
  best.reserve(2 * keep + options.batch);
  ParticleSet batch;
  std::vector<double> log_likelihood;
  for (std::size_t first = 0; first < total; first += options.batch) {
    const std::size_t count = std::min(options.batch, total - first);
    prepare_set(batch, count, scale_range.has_value());
    for (std::size_t j = 0; j < count; ++j) {
      const std::uint64_t id = first + j;
      const std::size_t k = id % scales, h = (id / scales) % headings, p = id / scales / headings;
      batch.x[j] = positions[p].x();
      batch.y[j] = positions[p].y();
      batch.theta[j] = heading_of(h);
      if (scale_range)
        batch.scale[j] = scale_of(k);
    }
    model.log_likelihood(scan, batch, log_likelihood, threads);
    for (std::size_t j = 0; j < count; ++j) {
      const double score = std::isnan(log_likelihood[j]) ? -std::numeric_limits<double>::infinity()
                                                         : log_likelihood[j];
      best.push_back({score, first + j});
    }
    if (best.size() >= 2 * keep) {
      std::nth_element(best.begin(), best.begin() + static_cast<std::ptrdiff_t>(keep), best.end(),
                       better);
      best.resize(keep);
    }
  }
  std::sort(best.begin(), best.end(), better);
  best.resize(keep);

  // The kept hypotheses become the particles.
  prepare_set(result.particles, keep, scale_range.has_value());
  const Eigen::Matrix2d grid_axes = rotation_2d(free_space.geometry().origin.theta);
  for (std::size_t i = 0; i < keep; ++i) {
    const std::uint64_t id = best[i].id;
    const std::size_t k = id % scales, h = (id / scales) % headings, p = id / scales / headings;
    Eigen::Vector2d position = positions[p];
    double theta = heading_of(h), scale = scale_of(k);
    if (options.jitter) {
      position += grid_axes * Eigen::Vector2d(random.uniform(-0.5, 0.5) * step,
                                              random.uniform(-0.5, 0.5) * step);
      theta += random.uniform(-0.5, 0.5) * heading_step;
      scale += random.uniform(-0.5, 0.5) * scale_step;
    }
    result.particles.x[i] = position.x();
    result.particles.y[i] = position.y();
    result.particles.theta[i] = normalize_angle(theta);
    if (scale_range)
      result.particles.scale[i] = std::max(kMinScale, scale);
  }
  result.scored = total;
  result.position_step = step;
  result.log_likelihood.reserve(best.size());
  for (const ScoredHypothesis& h : best)
    result.log_likelihood.push_back(h.score);
  result.best_log_likelihood = best.front().score;
  result.worst_kept_log_likelihood = best.back().score;
  return result;
}

}  // namespace floorgrid
