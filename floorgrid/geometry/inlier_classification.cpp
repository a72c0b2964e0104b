#include "floorgrid/geometry/inlier_classification.hpp"

#include <algorithm>
#include <cfloat>

#include "floorgrid/core/parallel.hpp"

namespace floorgrid {
namespace {

using Affine = Eigen::Matrix<double, 2, 3>;

// Pairs per reduction block: every block is summed on its own and the blocks are added in
// order, so the sums do not depend on how many threads share the blocks.
constexpr Eigen::Index kReductionBlock = Eigen::Index{1} << 15;
// Fewer pairs than this are not worth a second thread.
constexpr Eigen::Index kMinPairsPerThread = Eigen::Index{1} << 17;
// Pairs per vectorized chunk inside a block (a few kB: stays in L1).
constexpr Eigen::Index kChunk = 256;

using ChunkArray = Eigen::Array<double, Eigen::Dynamic, 1, Eigen::ColMajor, kChunk, 1>;

struct Sums {
  double w = 0, px = 0, py = 0, qx = 0, qy = 0, pxx = 0, pxy = 0, pyy = 0;
  double qxpx = 0, qxpy = 0, qypx = 0, qypy = 0, qq = 0, squared = 0, cost = 0;
  std::size_t inliers = 0, changed = 0;
  Eigen::Index first_bad = -1;

  void operator+=(const Sums& o) {
    w += o.w, px += o.px, py += o.py, qx += o.qx, qy += o.qy;
    pxx += o.pxx, pxy += o.pxy, pyy += o.pyy;
    qxpx += o.qxpx, qxpy += o.qxpy, qypx += o.qypx, qypy += o.qypy, qq += o.qq;
    squared += o.squared, cost += o.cost;
    inliers += o.inliers, changed += o.changed;
    if (first_bad < 0)
      first_bad = o.first_bad;
  }
};

struct Input {
  const double* plan;     // 2 x n, interleaved
  const double* grid;     // 2 x n, interleaved
  const double* weights;  // n, or null for all 1
  Eigen::Index size;      // n
  Affine relative;        // T about the origins: q - o_G = L (p - o_F) + t'
  Eigen::Vector2d origin_in_plan, origin_in_grid;
  double threshold2;
  std::uint8_t* mask;
  InlierPassMode mode;
};

// Asks for the chunk two ahead: the work per chunk is too short for the hardware prefetcher
// alone to keep the two streams of coordinates coming from memory.
void prefetch(const Input& in, Eigen::Index b) {
  constexpr Eigen::Index kLine = 64 / sizeof(double);
  const Eigen::Index n = std::min(kChunk, in.size - b);
  for (Eigen::Index k = 0; k < 2 * n; k += kLine) {
    __builtin_prefetch(in.plan + 2 * b + k);
    __builtin_prefetch(in.grid + 2 * b + k);
  }
}

// One chunk, copied into short arrays about the origins.
struct Chunk {
  ChunkArray px, py, qx, qy, w, d2;

  Chunk(const Input& in, Eigen::Index b, Eigen::Index n) {
    prefetch(in, b + 2 * kChunk);
    const Eigen::Map<const Eigen::Array2Xd> P(in.plan + 2 * b, 2, n);
    const Eigen::Map<const Eigen::Array2Xd> Q(in.grid + 2 * b, 2, n);
    px = P.row(0).transpose() - in.origin_in_plan.x();
    py = P.row(1).transpose() - in.origin_in_plan.y();
    qx = Q.row(0).transpose() - in.origin_in_grid.x();
    qy = Q.row(1).transpose() - in.origin_in_grid.y();
    if (in.weights) {
      w = Eigen::Map<const Eigen::ArrayXd>(in.weights + b, n);
    } else {
      w.setOnes(n);
    }
    const Affine& r = in.relative;
    d2 = (r(0, 0) * px + r(0, 1) * py + r(0, 2) - qx).square() +
         (r(1, 0) * px + r(1, 1) * py + r(1, 2) - qy).square();
  }
};

// Few pairs change between refits: their signed moments are added one by one.
void add_change(const Chunk& c, Eigen::Index k, double sign, Sums& s) {
  const double w = sign * c.w[k];
  s.w += w;
  s.px += w * c.px[k], s.py += w * c.py[k], s.qx += w * c.qx[k], s.qy += w * c.qy[k];
  s.pxx += w * c.px[k] * c.px[k], s.pxy += w * c.px[k] * c.py[k], s.pyy += w * c.py[k] * c.py[k];
  s.qxpx += w * c.qx[k] * c.px[k], s.qxpy += w * c.qx[k] * c.py[k];
  s.qypx += w * c.qy[k] * c.px[k], s.qypy += w * c.qy[k] * c.py[k];
  s.qq += w * (c.qx[k] * c.qx[k] + c.qy[k] * c.qy[k]);
}

// The moments of the pairs weighted by `we` (w for inliers, 0 otherwise), in one loop with
// four-lane accumulators: the compiler may not reorder a plain loop's floating-point sums, so
// the lanes are explicit (they become SIMD registers), and every array is read once.
void add_inlier_moments(const Chunk& c, const ChunkArray& we, Sums& s) {
  using Lanes = Eigen::Array4d;
  Lanes w = Lanes::Zero(), px = w, py = w, qx = w, qy = w, pxx = w, pxy = w, pyy = w;
  Lanes qxpx = w, qxpy = w, qypx = w, qypy = w, qq = w, squared = w;
  const Eigen::Index n = c.px.size();
  Eigen::Index k = 0;
  for (; k + 4 <= n; k += 4) {
    const Lanes e = we.segment<4>(k);
    const Lanes ex = e * c.px.segment<4>(k), ey = e * c.py.segment<4>(k);
    const Lanes x = c.px.segment<4>(k), y = c.py.segment<4>(k);
    const Lanes u = c.qx.segment<4>(k), v = c.qy.segment<4>(k);
    w += e, px += ex, py += ey, qx += e * u, qy += e * v;
    pxx += ex * x, pxy += ex * y, pyy += ey * y;
    qxpx += ex * u, qxpy += ey * u, qypx += ex * v, qypy += ey * v;
    qq += e * (u * u + v * v);
    squared += e * c.d2.segment<4>(k);
  }
  s.w += w.sum(), s.px += px.sum(), s.py += py.sum(), s.qx += qx.sum(), s.qy += qy.sum();
  s.pxx += pxx.sum(), s.pxy += pxy.sum(), s.pyy += pyy.sum();
  s.qxpx += qxpx.sum(), s.qxpy += qxpy.sum(), s.qypx += qypx.sum(), s.qypy += qypy.sum();
  s.qq += qq.sum(), s.squared += squared.sum();
  for (; k < n; ++k) {
    if (we[k] == 0.0)
      continue;
    add_change(c, k, 1.0, s);
    s.squared += we[k] * c.d2[k];
  }
}

void find_bad(const Chunk& c, Eigen::Index b, Sums& s) {
  if (s.first_bad >= 0)
    return;
  // x - x is 0 for finite x and NaN otherwise: one vectorized sum finds any NaN or infinity.
  const double probe = ((c.d2 - c.d2) + (c.w - c.w)).sum();
  if (probe == 0.0 && c.w.minCoeff() >= 0.0)
    return;
  for (Eigen::Index k = 0; k < c.d2.size(); ++k) {
    if (!(c.d2[k] <= DBL_MAX) || !(c.w[k] >= 0.0) || !(c.w[k] <= DBL_MAX)) {
      s.first_bad = b + k;
      return;
    }
  }
}

void classify_range(const Input& in, Eigen::Index begin, Eigen::Index end, Sums& s) {
  for (Eigen::Index b = begin; b < end; b += kChunk) {
    const Eigen::Index n = std::min(kChunk, end - b);
    const Chunk c(in, b, n);
    find_bad(c, b, s);
    // Plain element-wise loops (no sums): these vectorize.
    std::uint8_t now[kChunk];
    ChunkArray we(n);
    std::size_t inliers = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      now[k] = c.d2[k] <= in.threshold2 ? 1 : 0;
      we[k] = c.d2[k] <= in.threshold2 ? c.w[k] : 0.0;
    }
    for (Eigen::Index k = 0; k < n; ++k)
      inliers += now[k];
    std::uint8_t* mask = in.mask + b;
    if (in.mode == InlierPassMode::full) {
      add_inlier_moments(c, we, s);
      std::copy(now, now + n, mask);
      s.changed += inliers;
    } else {
      s.squared += (we * c.d2).sum();
      if (!std::equal(now, now + n, mask)) {
        for (Eigen::Index k = 0; k < n; ++k) {
          if (now[k] == mask[k])
            continue;
          add_change(c, k, now[k] ? 1.0 : -1.0, s);
          ++s.changed;
          mask[k] = now[k];
        }
      }
    }
    s.inliers += inliers;
  }
}

void cost_range(const Input& in, Eigen::Index begin, Eigen::Index end, Sums& s) {
  for (Eigen::Index b = begin; b < end; b += kChunk) {
    const Chunk c(in, b, std::min(kChunk, end - b));
    s.cost += (c.w * c.d2.min(in.threshold2)).sum();
  }
}

template <typename Range>
Sums over_blocks(Eigen::Index n, int threads, const Input& in, Range range) {
  const Eigen::Index blocks = (n + kReductionBlock - 1) / kReductionBlock;
  std::vector<Sums> partial(static_cast<std::size_t>(blocks));
  const auto run = [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index k = first; k < last; ++k) {
      range(in, k * kReductionBlock, std::min(n, (k + 1) * kReductionBlock),
            partial[static_cast<std::size_t>(k)]);
    }
  };
  // Per-block partial sums added in block order: the same sums whatever the split.
  parallel_blocks(static_cast<std::size_t>(blocks), n >= 2 * kMinPairsPerThread ? threads : 1,
                  [&](std::size_t first, std::size_t last) {
                    run(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last));
                  });
  Sums total;
  for (const Sums& p : partial)
    total += p;
  return total;
}

Input make_input(const ReferencePairs& pairs, const Affine& T, double threshold,
                 const Eigen::Vector2d& origin_in_plan, const Eigen::Vector2d& origin_in_grid) {
  Affine relative = T;
  relative.col(2) = T.leftCols<2>() * origin_in_plan + T.col(2) - origin_in_grid;
  return {pairs.points_in_plan.data(),
          pairs.points_in_grid.data(),
          pairs.has_weights() ? pairs.weights.data() : nullptr,
          pairs.size(),
          relative,
          origin_in_plan,
          origin_in_grid,
          threshold * threshold,
          nullptr,
          InlierPassMode::full};
}

}  // namespace

InlierPass classify_inliers(const ReferencePairs& pairs,
                            const Eigen::Matrix<double, 2, 3>& T_grid_plan, double inlier_threshold,
                            const Eigen::Vector2d& origin_in_plan,
                            const Eigen::Vector2d& origin_in_grid, InlierPassMode mode,
                            std::vector<std::uint8_t>& mask, int threads) {
  mask.resize(static_cast<std::size_t>(pairs.size()), 0);
  Input in = make_input(pairs, T_grid_plan, inlier_threshold, origin_in_plan, origin_in_grid);
  in.mask = mask.data();
  in.mode = mode;
  const Sums s = over_blocks(pairs.size(), threads, in, classify_range);
  InlierPass pass;
  pass.moments.origin_in_plan = origin_in_plan;
  pass.moments.origin_in_grid = origin_in_grid;
  pass.moments.weight = s.w;
  pass.moments.plan = {s.px, s.py};
  pass.moments.grid = {s.qx, s.qy};
  pass.moments.plan_plan << s.pxx, s.pxy, s.pxy, s.pyy;
  pass.moments.grid_plan << s.qxpx, s.qxpy, s.qypx, s.qypy;
  pass.moments.grid_grid = s.qq;
  pass.squared = s.squared;
  pass.inliers = s.inliers;
  pass.changed = s.changed;
  pass.first_bad = s.first_bad;
  return pass;
}

double msac_cost(const ReferencePairs& pairs, const Eigen::Matrix<double, 2, 3>& T_grid_plan,
                 double inlier_threshold, int threads) {
  // About the first pair: any origin keeps the residuals exact enough for a score.
  const Eigen::Vector2d origin_in_plan =
      pairs.size() > 0 ? Eigen::Vector2d(pairs.points_in_plan.col(0)) : Eigen::Vector2d::Zero();
  const Eigen::Vector2d origin_in_grid =
      pairs.size() > 0 ? Eigen::Vector2d(pairs.points_in_grid.col(0)) : Eigen::Vector2d::Zero();
  const Input in = make_input(pairs, T_grid_plan, inlier_threshold, origin_in_plan, origin_in_grid);
  return over_blocks(pairs.size(), threads, in, cost_range).cost;
}

}  // namespace floorgrid
