#include "floorgrid/localization/likelihood_field_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"
#include "floorgrid/core/validation.hpp"

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define FLOORGRID_LIKELIHOOD_FIELD_AVX2 1
#endif

namespace floorgrid {
namespace {

// Below this many particle-beam evaluations per thread, starting a thread costs more than it
// saves. A thread start is ~20 us on an idle machine and an evaluation ~1 ns, but on a shared
// one the started thread waits for a core: a tracking filter's scan (2,000 particles x 60
// beams, 0.1 ms) started one per scan, and `align`'s tracking passes over an hour of driving
// (54,000 scans) spent most of their wall clock waiting for them (60 s of 15 minutes' run for
// 3 s of CPU). Global localization (50,000 particles) still takes two. The scores do not
// depend on the split.
constexpr std::size_t kMinEvaluationsPerThread = 500'000;

}  // namespace

void validate_likelihood_field_options(const LikelihoodFieldOptions& o) {
  require_option(std::isfinite(o.sigma_hit) && o.sigma_hit > 0.0, "likelihood_field", "sigma_hit",
                 o.sigma_hit, "a finite number > 0 (metres)");
  require_option(std::isfinite(o.z_hit) && o.z_hit >= 0.0, "likelihood_field", "z_hit", o.z_hit,
                 "a finite number >= 0");
  require_option(std::isfinite(o.z_rand) && o.z_rand > 0.0, "likelihood_field", "z_rand", o.z_rand,
                 "a finite number > 0");
  require_option(std::isfinite(o.max_distance) && o.max_distance > 0.0, "likelihood_field",
                 "max_distance", o.max_distance, "a finite number > 0 (metres)");
  require_option(std::isfinite(o.beam_weight) && o.beam_weight > 0.0, "likelihood_field",
                 "beam_weight", o.beam_weight, "a finite number > 0");
  require_option(std::isfinite(o.known_margin) && o.known_margin >= 0.0, "likelihood_field",
                 "known_margin", o.known_margin, "a finite number >= 0 (metres)");
  require_option(o.min_known_share >= 0.0 && o.min_known_share <= 1.0, "likelihood_field",
                 "min_known_share", o.min_known_share, "in [0, 1]");
}

LikelihoodFieldModel::LikelihoodFieldModel(const OccupancyGrid& grid,
                                           const LikelihoodFieldOptions& options)
    : options_(options),
      cos_yaw_(std::cos(grid.geometry().origin.theta)),
      sin_yaw_(std::sin(grid.geometry().origin.theta)) {
  validate_likelihood_field_options(options_);
  if (grid.geometry().size() == 0)
    throw InputError("the map has no cells", {}, 0, "likelihood_field.map");
  distance_ = occupied_distance_field(grid, options_.max_distance);
  const int w = grid.width(), h = grid.height();
  stride_ = w + 2;
  max_u_ = static_cast<float>(w + 1);
  max_v_ = static_cast<float>(h + 1);
  const std::size_t table_size = static_cast<std::size_t>(w + 2) * (h + 2);
  const auto floor_log = static_cast<float>(std::log(options_.z_rand));
  log_p_.assign(table_size, floor_log);
  gaussian_.assign(table_size, 0.0f);
  known_.assign(table_size, 0);
  const DistanceField observed = observed_distance_field(grid, options_.known_margin + 1.0);
  const double inv_two_sigma2 = 1.0 / (2.0 * options_.sigma_hit * options_.sigma_hit);
  for (int iy = 0; iy < h; ++iy) {
    for (int ix = 0; ix < w; ++ix) {
      known_[static_cast<std::size_t>(iy + 1) * stride_ + (ix + 1)] =
          observed.at(ix, iy) <= options_.known_margin ? 1 : 0;
      if (!options_.unknown_is_free && grid.state(ix, iy) == CellState::unknown)
        continue;  // scores as off the map
      const double d = distance_.at(ix, iy);
      const double g = std::exp(-d * d * inv_two_sigma2);
      const std::size_t i = static_cast<std::size_t>(iy + 1) * stride_ + (ix + 1);
      gaussian_[i] = static_cast<float>(g);
      log_p_[i] = static_cast<float>(std::log(options_.z_hit * g + options_.z_rand));
    }
  }
}

LikelihoodFieldModel::CellTransform LikelihoodFieldModel::cell_transform(const Pose2& pose,
                                                                         double scale) const {
  const GridGeometry& g = distance_.geometry();
  const double px = pose.x - g.origin.x, py = pose.y - g.origin.y;
  // R(-yaw) (position - origin) / resolution, plus one for the table's border.
  const double x0 = (cos_yaw_ * px + sin_yaw_ * py) / g.resolution + 1.0;
  const double y0 = (-sin_yaw_ * px + cos_yaw_ * py) / g.resolution + 1.0;
  const double a = pose.theta - g.origin.theta;
  const double k = 1.0 / (scale * g.resolution);
  return {static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(std::cos(a) * k),
          static_cast<float>(std::sin(a) * k)};
}

std::size_t LikelihoodFieldModel::table_index(const Eigen::Vector2d& point_in_map) const {
  const Eigen::Vector2d c = distance_.geometry().to_cell_coordinates(point_in_map);
  // std::max(0, NaN) is 0: a NaN point lands on the border.
  const double u = std::min(std::max(0.0, c.x() + 1.0), static_cast<double>(max_u_));
  const double v = std::min(std::max(0.0, c.y() + 1.0), static_cast<double>(max_v_));
  return static_cast<std::size_t>(v) * stride_ + static_cast<std::size_t>(u);
}

double LikelihoodFieldModel::distance_to_occupied(const Eigen::Vector2d& point_in_map) const {
  return distance_.at(point_in_map);
}

double LikelihoodFieldModel::point_log_likelihood(const Eigen::Vector2d& point_in_map) const {
  return log_p_[table_index(point_in_map)];
}

void LikelihoodFieldModel::log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                                          std::vector<double>& out, int threads) const {
  const std::size_t n = particles.size();
  out.assign(n, 0.0);
  const std::size_t beams = scan.size();
  if (n == 0 || beams == 0)
    return;
  // Endpoints padded to whole blocks of 8 (the pad lanes' values are masked out).
  const std::size_t padded = (beams + 7) / 8 * 8;
  std::vector<float> ex(padded, 0.0f), ey(padded, 0.0f);
  std::copy_n(scan.end_x.begin(), beams, ex.begin());
  std::copy_n(scan.end_y.begin(), beams, ey.begin());
  const float* log_p = log_p_.data();
  const double weight = options_.beam_weight;

  const auto score_block = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const CellTransform t = cell_transform({particles.x[i], particles.y[i], particles.theta[i]},
                                             particles.scale_of(i));
#ifdef FLOORGRID_LIKELIHOOD_FIELD_AVX2
      const __m256 x0 = _mm256_set1_ps(t.x0), y0 = _mm256_set1_ps(t.y0);
      const __m256 c = _mm256_set1_ps(t.c), s = _mm256_set1_ps(t.s);
      const __m256 zero = _mm256_setzero_ps();
      const __m256 max_u = _mm256_set1_ps(max_u_), max_v = _mm256_set1_ps(max_v_);
      const __m256i stride = _mm256_set1_epi32(stride_);
      __m256 sum = _mm256_setzero_ps();
      for (std::size_t k = 0; k < padded; k += 8) {
        const __m256 bx = _mm256_loadu_ps(ex.data() + k);
        const __m256 by = _mm256_loadu_ps(ey.data() + k);
        // u = x0 + c bx - s by, v = y0 + s bx + c by; max(u, 0) first maps NaN to 0.
        __m256 u = _mm256_fmadd_ps(c, bx, _mm256_fnmadd_ps(s, by, x0));
        __m256 v = _mm256_fmadd_ps(s, bx, _mm256_fmadd_ps(c, by, y0));
        u = _mm256_min_ps(_mm256_max_ps(u, zero), max_u);
        v = _mm256_min_ps(_mm256_max_ps(v, zero), max_v);
        const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(v), stride),
                                               _mm256_cvttps_epi32(u));
        __m256 value = _mm256_i32gather_ps(log_p, index, 4);
        if (k + 8 > beams) {
          const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
          const __m256i live =
              _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<int>(beams - k)), lane);
          value = _mm256_and_ps(value, _mm256_castsi256_ps(live));
        }
        sum = _mm256_add_ps(sum, value);
      }
      const __m128 half = _mm_add_ps(_mm256_castps256_ps128(sum), _mm256_extractf128_ps(sum, 1));
      const __m128 quarter = _mm_add_ps(half, _mm_movehl_ps(half, half));
      const __m128 one = _mm_add_ss(quarter, _mm_shuffle_ps(quarter, quarter, 1));
      out[i] = weight * static_cast<double>(_mm_cvtss_f32(one));
#else
      float sum = 0.0f;
      for (std::size_t k = 0; k < beams; ++k) {
        const float u = std::min(std::max(0.0f, t.x0 + t.c * ex[k] - t.s * ey[k]), max_u_);
        const float v = std::min(std::max(0.0f, t.y0 + t.s * ex[k] + t.c * ey[k]), max_v_);
        sum += log_p[static_cast<std::size_t>(v) * stride_ + static_cast<std::size_t>(u)];
      }
      out[i] = weight * static_cast<double>(sum);
#endif
    }
  };
  parallel_blocks(n, threads_for(n * beams, kMinEvaluationsPerThread, threads), score_block);
}

double LikelihoodFieldModel::mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                                                  double scale) const {
  const std::size_t beams = scan.size();
  const CellTransform t = cell_transform(pose, scale);
  double sum = 0.0;
  std::size_t known = 0;
  for (std::size_t k = 0; k < beams; ++k) {
    const float ex = scan.end_x[k], ey = scan.end_y[k];
    const float u = std::min(std::max(0.0f, t.x0 + t.c * ex - t.s * ey), max_u_);
    const float v = std::min(std::max(0.0f, t.y0 + t.s * ex + t.c * ey), max_v_);
    const std::size_t i = static_cast<std::size_t>(v) * stride_ + static_cast<std::size_t>(u);
    if (!known_[i])
      continue;
    sum += gaussian_[i];
    ++known;
  }
  if (known == 0 ||
      static_cast<double>(known) < options_.min_known_share * static_cast<double>(beams))
    return std::numeric_limits<double>::quiet_NaN();
  return sum / static_cast<double>(known);
}

}  // namespace floorgrid
