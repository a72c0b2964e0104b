#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::test {

/// A known plan -> grid similarity: grid = scale * R(yaw) * plan + t.
struct KnownSimilarity {
  double scale = 1.0;
  double yaw = 0.0;
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
    return scale * rotation_2d(yaw) * p + t;
  }
};

/// Pairs of `truth` on a lattice over [x0, x1] x [y0, y1] (plan metres), 9 x 7 points.
template <typename Truth>
ReferencePairs lattice_pairs(const Truth& truth, double x0, double x1, double y0, double y1,
                             int nx = 9, int ny = 7) {
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, nx * ny);
  pairs.points_in_grid.resize(2, nx * ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d p(x0 + (x1 - x0) * i / (nx - 1), y0 + (y1 - y0) * j / (ny - 1));
      pairs.points_in_plan.col(j * nx + i) = p;
      pairs.points_in_grid.col(j * nx + i) = truth(p);
    }
  }
  return pairs;
}

/// A smooth bend on top of a similarity (non-rigid truth): up to ~0.3 m over 20 m.
struct BentTruth {
  KnownSimilarity similarity;
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = similarity(p);
    return q + Eigen::Vector2d(0.0, 0.3 * std::sin(p.x() / 8.0));
  }
};

/// Whether a program is on PATH.
inline bool have_program(const std::string& name) {
  return run_command("command -v " + name + " >/dev/null 2>&1").status == 0;
}

}  // namespace floorgrid::test
