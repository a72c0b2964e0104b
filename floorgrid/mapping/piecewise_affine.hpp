#pragma once

#include <memory>
#include <vector>

#include "floorgrid/mapping/delaunay.hpp"
#include "floorgrid/mapping/fold_index.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// `dt` (thesis 3.4, 4.5): the Delaunay triangulation of the plan points (exact predicates);
/// a plan point maps with its barycentric coordinates into the partner triangle on the grid
/// (eq. 4.20-4.23). Outside the hull a point keeps the mapped nearest hull point and moves from
/// it by the linear part of the pairs' least-squares similarity: continuous at the hull and
/// bounded however thin the hull's triangles (extrapolating a sliver's own affine map throws
/// points tens of metres off). The map is continuous and piecewise affine.
///
/// Dense laser pairs lie closer together than their noise, so some grid triangles come out
/// flipped against their plan triangles: the map folds there and a grid point has several plan
/// points. The fit untangles: while a triangle folds (or a hull edge's outside strip does), it
/// drops the pair among its corners that disagrees most with its Delaunay neighbours (the
/// largest Laplacian of the displacement from the pairs' similarity) and triangulates again, up
/// to a quarter of the pairs. The inverse is exact: it collects every plan point that maps to the
/// grid point (the triangles holding it, the outside strips and corner wedges holding it) and is
/// invertible only when there is exactly one, so that it never returns another preimage than
/// the one a point came from.
class PiecewiseAffineMapping : public PointMapping {
 public:
  /// A dt model; `untangle` false keeps every pair, folds and all (a ground truth through hand
  /// pairs, as the thesis).
  explicit PiecewiseAffineMapping(MappingCommonOptions common, bool untangle = true);
  ~PiecewiseAffineMapping() override;

  std::string name() const override { return "dt"; }
  std::size_t min_pairs() const override { return 3; }
  bool needs_non_collinear() const override { return true; }
  bool reduces_pairs() const override { return true; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;
  InverseMapping inverse(const Eigen::Vector2d& point_in_grid) const override;

  /// Triangles whose grid partner is flipped (the map folds there).
  std::size_t folded_triangles() const;
  /// Pairs the fit dropped to untangle folds.
  std::size_t untangled_pairs() const { return untangled_; }

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  /// Triangulates the pairs and marks the folded triangles.
  void build(const ReferencePairs& pairs);
  /// Indexes the grid triangles for the inverse (once the pairs are final).
  void index_grid_triangles();
  /// The pairs left after dropping those that make the map fold (see the class comment).
  ReferencePairs untangle(const ReferencePairs& pairs);
  /// Whether hull edge k's outside strip keeps the orientation (its grid edge turns the same way
  /// against the similarity's image of the plan edge's outward normal).
  bool hull_edge_folds(std::size_t k) const;
  /// The plan points outside the hull that map to `g` (strips and corner wedges), appended.
  void outside_preimages(const Eigen::Vector2d& g, std::vector<Eigen::Vector2d>& out) const;
  Eigen::Vector2d map_in(int triangle, const Eigen::Vector3d& barycentric) const;
  /// The map of `point` located at `located` (inside: its triangle; outside: the hull rule).
  Eigen::Vector2d map_located(const Eigen::Vector2d& point,
                              const DelaunayTriangulation::Located& located) const;

  ReferencePairs pairs_;
  std::unique_ptr<DelaunayTriangulation> triangulation_;
  std::vector<bool> folded_;  ///< per triangle
  bool untangle_ = true;
  std::size_t untangled_ = 0;
  GridBoxIndex grid_triangles_;  ///< the triangles' grid boxes, for the inverse
};

}  // namespace floorgrid
