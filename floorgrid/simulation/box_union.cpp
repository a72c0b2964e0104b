#include "floorgrid/simulation/box_union.hpp"

#include <algorithm>
#include <map>

namespace floorgrid {

namespace {

std::vector<double> sorted_unique(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::size_t index_of(const std::vector<double>& sorted, double value) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), value) -
                                  sorted.begin());
}

}  // namespace

bool inside_any(const std::vector<Eigen::AlignedBox2d>& boxes, const Eigen::Vector2d& point) {
  return std::any_of(boxes.begin(), boxes.end(),
                     [&](const Eigen::AlignedBox2d& b) { return b.contains(point); });
}

BoxUnionOutline box_union_outline(const std::vector<Eigen::AlignedBox2d>& boxes) {
  std::vector<double> xs, ys;
  for (const auto& b : boxes) {
    if (b.isEmpty())
      continue;
    xs.push_back(b.min().x());
    xs.push_back(b.max().x());
    ys.push_back(b.min().y());
    ys.push_back(b.max().y());
  }
  xs = sorted_unique(xs);
  ys = sorted_unique(ys);
  BoxUnionOutline out;
  if (xs.size() < 2 || ys.size() < 2)
    return out;
  const std::size_t nx = xs.size() - 1, ny = ys.size() - 1;
  std::vector<char> inside(nx * ny, 0);
  for (const auto& b : boxes) {
    if (b.isEmpty())
      continue;
    const std::size_t x0 = index_of(xs, b.min().x()), x1 = index_of(xs, b.max().x());
    const std::size_t y0 = index_of(ys, b.min().y()), y1 = index_of(ys, b.max().y());
    for (std::size_t j = y0; j < y1; ++j) {
      for (std::size_t i = x0; i < x1; ++i)
        inside[j * nx + i] = 1;
    }
  }
  const auto in = [&](long i, long j) {
    if (i < 0 || j < 0 || i >= static_cast<long>(nx) || j >= static_cast<long>(ny))
      return false;
    return inside[static_cast<std::size_t>(j) * nx + static_cast<std::size_t>(i)] != 0;
  };
  // Horizontal boundary pieces on line y = ys[j], oriented so that the inside is on the left,
  // merged into maximal runs with the same orientation.
  for (long j = 0; j <= static_cast<long>(ny); ++j) {
    int run = 0;  // +1: inside below (edge runs -x), -1: inside above (edge runs +x)
    long start = 0;
    for (long i = 0; i <= static_cast<long>(nx); ++i) {
      int kind = 0;
      if (i < static_cast<long>(nx)) {
        const bool below = in(i, j - 1), above = in(i, j);
        kind = below == above ? 0 : (below ? 1 : -1);
      }
      if (kind != run) {
        if (run != 0) {
          const Eigen::Vector2d a(xs[start], ys[j]), b(xs[i], ys[j]);
          out.edges.push_back(run < 0 ? Segment{a, b, 0} : Segment{b, a, 0});
        }
        run = kind;
        start = i;
      }
    }
  }
  for (long i = 0; i <= static_cast<long>(nx); ++i) {
    int run = 0;
    long start = 0;
    for (long j = 0; j <= static_cast<long>(ny); ++j) {
      int kind = 0;
      if (j < static_cast<long>(ny)) {
        const bool left = in(i - 1, j), right = in(i, j);
        kind = left == right ? 0 : (left ? 1 : -1);
      }
      if (kind != run) {
        if (run != 0) {
          const Eigen::Vector2d a(xs[i], ys[start]), b(xs[i], ys[j]);
          out.edges.push_back(run > 0 ? Segment{a, b, 0} : Segment{b, a, 0});
        }
        run = kind;
        start = j;
      }
    }
  }
  // Corners: outline vertices where a horizontal and a vertical edge meet.
  std::map<std::pair<double, double>, int> ends;
  for (const Segment& s : out.edges) {
    const bool horizontal = s.a.y() == s.b.y();
    for (const auto& p : {s.a, s.b})
      ends[{p.x(), p.y()}] |= horizontal ? 1 : 2;
  }
  for (const auto& [p, kinds] : ends) {
    if (kinds == 3)
      out.corners.emplace_back(p.first, p.second);
  }
  return out;
}

}  // namespace floorgrid
