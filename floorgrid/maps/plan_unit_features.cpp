#include "floorgrid/maps/plan_unit_features.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <tuple>

namespace floorgrid {

namespace {

/// A line prepared for the band search: direction, normal, length, angle bucket.
struct Oriented {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d mid = Eigen::Vector2d::Zero();
  Eigen::Vector2d d = Eigen::Vector2d::UnitX();  ///< unit direction, angle in [0, pi)
  Eigen::Vector2d n = Eigen::Vector2d::UnitY();  ///< unit normal, d turned left
  double length = 0.0;
  int bucket = 0;
};

/// Nearest parallel, overlapping neighbours of one line on its two sides.
struct SideGaps {
  std::optional<double> left;   ///< along +n
  std::optional<double> right;  ///< along -n
};

/// The weighted median of `values` (weights > 0); 0 when empty.
double weighted_median(std::vector<std::pair<double, double>> values) {
  if (values.empty()) {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  double total = 0.0;
  for (const auto& [v, w] : values) {
    total += w;
  }
  double seen = 0.0;
  for (const auto& [v, w] : values) {
    seen += w;
    if (seen >= total / 2.0) {
      return v;
    }
  }
  return values.back().first;
}

/// The most common value of a positive, weighted sample: the peak of a histogram of log10
/// values in bins of 0.05 (12%), smoothed over neighbouring bins, refined to the weighted median
/// of the samples in the peak's +-25%.
std::pair<double, double> weighted_mode(const std::vector<std::pair<double, double>>& values) {
  constexpr double kBin = 0.05;
  double lo = HUGE_VAL, hi = -HUGE_VAL, total = 0.0;
  for (const auto& [v, w] : values) {
    lo = std::min(lo, std::log10(v));
    hi = std::max(hi, std::log10(v));
    total += w;
  }
  const std::size_t bins = static_cast<std::size_t>((hi - lo) / kBin) + 1;
  std::vector<double> histogram(bins + 2, 0.0);
  for (const auto& [v, w] : values) {
    histogram[1 + static_cast<std::size_t>((std::log10(v) - lo) / kBin)] += w;
  }
  std::size_t peak = 1;
  double best = -1.0;
  for (std::size_t i = 1; i <= bins; ++i) {
    const double smoothed = histogram[i - 1] + 2.0 * histogram[i] + histogram[i + 1];
    if (smoothed > best) {
      best = smoothed;
      peak = i;
    }
  }
  const double centre = std::pow(10.0, lo + (static_cast<double>(peak) - 0.5) * kBin);
  std::vector<std::pair<double, double>> near;
  double near_weight = 0.0;
  for (const auto& [v, w] : values) {
    if (v >= centre / 1.25 && v <= centre * 1.25) {
      near.emplace_back(v, w);
      near_weight += w;
    }
  }
  return {weighted_median(near), total > 0.0 ? near_weight / total : 0.0};
}

std::vector<Oriented> orient(const std::vector<PlanLine>& lines, int buckets) {
  std::vector<Oriented> out;
  out.reserve(lines.size());
  for (const PlanLine& line : lines) {
    Eigen::Vector2d d = line.b - line.a;
    const double length = d.norm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      continue;
    }
    d /= length;
    if (d.y() < 0.0 || (d.y() == 0.0 && d.x() < 0.0)) {
      d = -d;  // angle in [0, pi): a line has no direction
    }
    const double angle = std::atan2(d.y(), d.x());
    Oriented o;
    o.a = line.a;
    o.mid = 0.5 * (line.a + line.b);
    o.d = d;
    o.n = Eigen::Vector2d(-d.y(), d.x());
    o.length = length;
    o.bucket = std::min(buckets - 1, static_cast<int>(angle / std::numbers::pi * buckets));
    out.push_back(o);
  }
  return out;
}

/// The gap from line `i` to line `j` (signed along i's normal) if they are parallel and overlap
/// side by side, else nullopt. Collinear lines (gap ~0) are not neighbours.
std::optional<double> parallel_gap(const Oriented& i, const Oriented& j,
                                   const WallBandOptions& options) {
  const double cross = i.d.x() * j.d.y() - i.d.y() * j.d.x();
  if (std::abs(cross) > std::sin(options.max_angle)) {
    return std::nullopt;
  }
  const double gap = i.n.dot(j.mid - i.a);
  if (std::abs(gap) <= 1e-6 * i.length) {
    return std::nullopt;
  }
  const double u0 = i.d.dot(j.mid - 0.5 * j.length * j.d - i.a);
  const double u1 = i.d.dot(j.mid + 0.5 * j.length * j.d - i.a);
  const double overlap = std::min(std::max(u0, u1), i.length) - std::max(std::min(u0, u1), 0.0);
  if (overlap < options.min_overlap * std::min(i.length, j.length)) {
    return std::nullopt;
  }
  return gap;
}

/// Fills `gaps` for the lines of angle bucket `b`. Lines within max_angle of them lie in the
/// bucket or its two neighbours (the first and last are neighbours: angles wrap at pi). In the
/// bucket's frame (along its direction, offset along its normal) the lines are cut into cells
/// along the direction, each cell's lines sorted by offset: a line's neighbours are found by
/// walking away from it, in the cell of its midpoint, on both sides, so that the many collinear
/// pieces of a regular building (every room's wall on one grid line) are not walked through.
void find_side_gaps(const std::vector<Oriented>& lines,
                    const std::vector<std::vector<std::size_t>>& by_bucket, int b,
                    const WallBandOptions& options, std::vector<SideGaps>& gaps) {
  const int buckets = static_cast<int>(by_bucket.size());
  const double angle = (b + 0.5) * std::numbers::pi / buckets;
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d normal(-along.y(), along.x());
  std::vector<std::size_t> members;
  std::vector<double> lengths;
  std::vector<std::pair<double, double>> spans;  // along the bucket's direction
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const int nb : {b - 1, b, b + 1}) {
    for (const std::size_t j : by_bucket[static_cast<std::size_t>((nb + buckets) % buckets)]) {
      const Oriented& l = lines[j];
      const double half = 0.5 * l.length * std::abs(along.dot(l.d));
      members.push_back(j);
      lengths.push_back(l.length);
      spans.emplace_back(along.dot(l.mid) - half, along.dot(l.mid) + half);
      lo = std::min(lo, spans.back().first);
      hi = std::max(hi, spans.back().second);
    }
  }
  // Cells about as long as the longer lines (the 90th percentile), coarsened until the cut
  // lines make at most a few entries per line (a few huge lines among tiny ones), and never
  // finer than 1e-12 of the drawing (cell numbers stay exact integers).
  const auto p90 =
      lengths.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(lengths.size() - 1));
  std::nth_element(lengths.begin(), p90, lengths.end());
  double cell = std::max({*p90, (hi - lo) * 1e-12, 1e-300});
  const double budget = 8.0 * static_cast<double>(members.size()) + 1e5;
  for (;;) {
    double needed = 0.0;
    for (const auto& [u0, u1] : spans) {
      needed += std::floor((u1 - lo) / cell) - std::floor((u0 - lo) / cell) + 1.0;
    }
    if (needed <= budget) {
      break;
    }
    cell *= 2.0;
  }
  struct Entry {
    std::int64_t cell;
    double offset;
    std::size_t line;
    bool operator<(const Entry& o) const {
      return std::tie(cell, offset, line) < std::tie(o.cell, o.offset, o.line);
    }
  };
  std::vector<Entry> entries;
  for (std::size_t m = 0; m < members.size(); ++m) {
    const auto c0 = static_cast<std::int64_t>(std::floor((spans[m].first - lo) / cell));
    const auto c1 = static_cast<std::int64_t>(std::floor((spans[m].second - lo) / cell));
    for (std::int64_t c = c0; c <= c1; ++c) {
      entries.push_back({c, normal.dot(lines[members[m]].mid), members[m]});
    }
  }
  std::sort(entries.begin(), entries.end());
  for (const std::size_t i : by_bucket[static_cast<std::size_t>(b)]) {
    const Oriented& line = lines[i];
    const Entry self{static_cast<std::int64_t>(std::floor((along.dot(line.mid) - lo) / cell)),
                     normal.dot(line.mid), i};
    const auto first =
        std::lower_bound(entries.begin(), entries.end(), Entry{self.cell, -HUGE_VAL, 0});
    const auto last =
        std::lower_bound(entries.begin(), entries.end(), Entry{self.cell + 1, -HUGE_VAL, 0});
    const auto at = std::lower_bound(first, last, self);
    SideGaps& side = gaps[i];
    for (const int step : {1, -1}) {
      const std::optional<double>& nearest = step > 0 ? side.left : side.right;
      auto it = at;
      for (std::size_t s = 0; s < options.max_scan; ++s) {
        if (step > 0 && ++it == last) {
          break;
        }
        if (step < 0) {
          if (it == first) {
            break;
          }
          --it;
        }
        if (nearest && std::abs(it->offset - self.offset) > 1.05 * *nearest) {
          break;
        }
        const auto gap =
            it->line == i ? std::nullopt : parallel_gap(line, lines[it->line], options);
        if (!gap) {
          continue;
        }
        std::optional<double>& same_side = *gap > 0.0 ? side.left : side.right;
        if (!same_side || std::abs(*gap) < *same_side) {
          same_side = std::abs(*gap);
        }
      }
    }
  }
}

}  // namespace

std::vector<PlanArc> find_door_leaves(const std::vector<PlanCircle>& arcs,
                                      const std::vector<PlanLine>& lines) {
  // Line ends sorted by x, each with the other end of its line.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> ends;
  ends.reserve(2 * lines.size());
  for (const PlanLine& line : lines) {
    ends.emplace_back(line.a, line.b);
    ends.emplace_back(line.b, line.a);
  }
  std::sort(ends.begin(), ends.end(),
            [](const auto& p, const auto& q) { return p.first.x() < q.first.x(); });
  constexpr double kAligned = 0.9986;  // cos(3 degrees)
  std::vector<PlanArc> out;
  out.reserve(arcs.size());
  for (const PlanCircle& arc : arcs) {
    PlanArc evidence{arc.radius, arc.end - arc.start, false};
    if (evidence.sweep < std::numbers::pi && arc.radius > 0.0) {
      const double tolerance = 0.05 * arc.radius;
      const Eigen::Vector2d towards[] = {{std::cos(arc.start), std::sin(arc.start)},
                                         {std::cos(arc.end), std::sin(arc.end)}};
      auto it = std::lower_bound(ends.begin(), ends.end(), arc.center.x() - tolerance,
                                 [](const auto& end, double x) { return end.first.x() < x; });
      for (; it != ends.end() && it->first.x() <= arc.center.x() + tolerance && !evidence.leaf;
           ++it) {
        if ((it->first - arc.center).norm() > tolerance) {
          continue;
        }
        const Eigen::Vector2d along = it->second - arc.center;
        const double length = along.norm();
        if (length < 0.8 * arc.radius || length > 1.2 * arc.radius) {
          continue;
        }
        for (const Eigen::Vector2d& t : towards) {
          evidence.leaf = evidence.leaf || along.dot(t) / length >= kAligned;
        }
      }
    }
    out.push_back(evidence);
  }
  return out;
}

WallBandSummary measure_wall_bands(const std::vector<PlanLine>& lines,
                                   const WallBandOptions& options) {
  const int buckets =
      std::max(3, static_cast<int>(std::ceil(std::numbers::pi / options.max_angle)));
  const std::vector<Oriented> oriented = orient(lines, buckets);
  std::vector<std::vector<std::size_t>> by_bucket(static_cast<std::size_t>(buckets));
  for (std::size_t i = 0; i < oriented.size(); ++i) {
    by_bucket[static_cast<std::size_t>(oriented[i].bucket)].push_back(i);
  }

  std::vector<SideGaps> gaps(oriented.size());
  for (int b = 0; b < buckets; ++b) {
    if (!by_bucket[static_cast<std::size_t>(b)].empty()) {
      find_side_gaps(oriented, by_bucket, b, options, gaps);
    }
  }

  std::vector<std::pair<double, double>> thickness, spacing;
  for (std::size_t i = 0; i < oriented.size(); ++i) {
    const SideGaps& side = gaps[i];
    if (!side.left && !side.right) {
      continue;
    }
    const double near = std::min(side.left.value_or(HUGE_VAL), side.right.value_or(HUGE_VAL));
    const std::optional<double> far = side.left && side.right
                                          ? std::optional<double>(std::max(*side.left, *side.right))
                                          : std::nullopt;
    if (far && *far < options.min_ratio * near) {
      continue;  // evenly spaced lines (single-line walls, stairs, hatching): not a band
    }
    thickness.emplace_back(near, oriented[i].length);
    if (far) {
      spacing.emplace_back(*far, oriented[i].length);
    }
  }
  WallBandSummary summary;
  summary.faces = thickness.size();
  if (!thickness.empty()) {
    std::tie(summary.thickness, summary.thickness_share) = weighted_mode(thickness);
  }
  summary.spacing = weighted_median(spacing);
  return summary;
}

Eigen::AlignedBox2d core_extent(std::vector<Eigen::Vector2d> points, double tail) {
  Eigen::AlignedBox2d box;
  if (points.empty()) {
    return box;
  }
  const std::size_t n = points.size();
  const auto lo = static_cast<std::size_t>(std::floor(tail * static_cast<double>(n - 1)));
  const auto hi = static_cast<std::size_t>(std::ceil((1.0 - tail) * static_cast<double>(n - 1)));
  for (int axis = 0; axis < 2; ++axis) {
    const auto by_axis = [axis](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
      return p(axis) < q(axis);
    };
    std::nth_element(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(lo), points.end(),
                     by_axis);
    box.min()(axis) = points[lo](axis);
    std::nth_element(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(hi), points.end(),
                     by_axis);
    box.max()(axis) = points[hi](axis);
  }
  return box;
}

}  // namespace floorgrid
