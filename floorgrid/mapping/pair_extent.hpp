#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid {

/// The box of the bulk of `points`: per axis, from the (k+1)-th smallest to the (k+1)-th largest
/// coordinate, k = ceil(trim * n) (at least 1 from 5 points on; none below), so that a few far
/// points do not stretch it. Empty points: an empty box.
Eigen::AlignedBox2d robust_box(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                               double trim = 0.01);

/// The longer side of robust_box(points, trim), metres (0 for fewer than two distinct points).
double robust_extent(const Eigen::Ref<const Eigen::Matrix2Xd>& points, double trim = 0.01);

/// What makes a pair far from the others.
struct FarPairOptions {
  double trim = 0.01;         ///< fraction of the pairs left out at each end of robust_box
  double factor = 10.0;       ///< far: more than this many robust extents outside the box
  std::size_t min_pairs = 5;  ///< fewer pairs than this: none is judged far
};

/// A pair far outside the bulk of the pairs (a typo, a unit slip), on one side.
struct FarPair {
  Eigen::Index index = 0;  ///< 0-based, in the pairs given
  std::string side;        ///< "plan" or "grid"
  int axis = 0;            ///< 0 (x) or 1 (y): the coordinate farther outside the box
  double distance = 0.0;   ///< metres outside that side's robust_box
  double extent = 0.0;     ///< metres, that box's longer side
};

/// The pairs whose plan or grid point lies more than options.factor robust extents outside that
/// side's robust_box (the plan side named first when both are), in their order. One far pair
/// makes every extent-based choice (cells, blocks, lattices, hulls) about it, not the building.
std::vector<FarPair> far_pairs(const ReferencePairs& pairs, const FarPairOptions& options = {});

}  // namespace floorgrid
