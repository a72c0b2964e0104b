#include "floorgrid/io/plans/dxf_entities.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_curves.hpp"
#include "floorgrid/io/plans/dxf_dimensions.hpp"

namespace floorgrid::io {

namespace {

using Curve = decltype(DrawingItem::curve);
using Curves = std::vector<Curve>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr std::size_t kMaxBlockDepth = 64;
constexpr std::size_t kWarningsPerKind = 10;

const std::set<std::string> kAnnotation = {"TEXT",
                                           "MTEXT",
                                           "ATTRIB",
                                           "ATTDEF",
                                           "DIMENSION",
                                           "ARC_DIMENSION",
                                           "LARGE_RADIAL_DIMENSION",
                                           "LEADER",
                                           "MULTILEADER",
                                           "MLEADER",
                                           "TOLERANCE",
                                           "HATCH",
                                           "POINT",
                                           "VIEWPORT"};

std::string at_line(const DxfEntity& e) {
  return e.type + " at line " + std::to_string(e.line);
}

/// The transform from an entity's object coordinate system to the world: `T` after the OCS.
Eigen::Affine3d through_ocs(const Eigen::Affine3d& T, const DxfEntity& e) {
  Eigen::Affine3d ocs = Eigen::Affine3d::Identity();
  ocs.linear() = ocs_axes(e.extrusion());
  return T * ocs;
}

Eigen::Vector2d world_xy(const Eigen::Affine3d& M, const Eigen::Vector3d& p) {
  return (M * p).head<2>();
}

/// Appends the arc from `a0` to `a1` (counter-clockwise, radians) of the circle in the OCS
/// plane through `center`, as mapped by `M` onto world XY: an arc when the map is a similarity
/// there (a mirror flips the sweep), else an elliptical curve.
void add_arc(const Eigen::Affine3d& M, const Eigen::Vector3d& center, double radius, double a0,
             double a1, Curves& out) {
  const Eigen::Matrix2d A = M.linear().topLeftCorner<2, 2>();
  const Eigen::Vector2d c = world_xy(M, center);
  const Eigen::Vector2d ex = A.col(0), ey = A.col(1);
  const double sx = ex.norm(), sy = ey.norm();
  const double tol = 1e-9 * std::max(sx, sy);
  if (sx > 0.0 && std::abs(sx - sy) <= tol && std::abs(ex.dot(ey)) <= tol * std::max(sx, sy)) {
    const double theta = std::atan2(ex.y(), ex.x());
    const bool mirrored = A.determinant() < 0.0;
    // A mirror maps the direction at angle t to theta - t, so the sweep runs the other way.
    out.push_back(CircularArc2{c, radius * sx, mirrored ? theta - a1 : theta + a0,
                               mirrored ? theta - a0 : theta + a1});
  } else {
    out.push_back(DrawingEllipse{c, radius * ex, radius * ey, a0, a1});
  }
}

/// End angle after `start` of a DXF angle pair: equal angles are a full turn.
double sweep_end(double start, double end) {
  double sweep = std::fmod(end - start, kTwoPi);
  if (sweep <= 0.0) {
    sweep += kTwoPi;
  }
  return start + sweep;
}

struct PolyVertex {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double bulge = 0.0;
};

/// Straight and bulged pieces of a 2D polyline whose vertices lie in the OCS plane at `elevation`.
void add_polyline(const Eigen::Affine3d& M, const std::vector<PolyVertex>& v, bool closed,
                  double elevation, Curves& out) {
  const std::size_t n = v.size();
  // Closed with two vertices is still two pieces: two bulges make AutoCAD's DONUT, a circle.
  const std::size_t pieces = closed && n >= 2 ? n : (n > 0 ? n - 1 : 0);
  for (std::size_t i = 0; i < pieces; ++i) {
    const PolyVertex& a = v[i];
    const PolyVertex& b = v[(i + 1) % n];
    if (a.p == b.p) {
      continue;  // repeated vertices draw nothing
    }
    if (a.bulge == 0.0) {
      out.push_back(DrawingLine{world_xy(M, {a.p.x(), a.p.y(), elevation}),
                                world_xy(M, {b.p.x(), b.p.y(), elevation})});
    } else {
      const CircularArc2 arc = bulge_arc(a.p, b.p, a.bulge);
      add_arc(M, {arc.center.x(), arc.center.y(), elevation}, arc.radius, arc.start, arc.end, out);
    }
  }
}

void lwpolyline_curves(const DxfEntity& e, const Eigen::Affine3d& T, Curves& out) {
  std::vector<PolyVertex> v;
  for (const DxfGroup& g : e.groups) {
    if (g.code == 10) {
      v.push_back({{group_double(g), 0.0}, 0.0});
    }
    if (v.empty()) {
      continue;
    }
    if (g.code == 20) {
      v.back().p.y() = group_double(g);
    }
    if (g.code == 42) {
      v.back().bulge = group_double(g);
    }
  }
  add_polyline(through_ocs(T, e), v, (e.integer(70, 0) & 1) != 0, e.number(38), out);
}

/// Old-style POLYLINE: 2D (OCS, bulges) or 3D (world); false for meshes, which are not plans.
bool polyline_curves(const DxfEntity& e, const Eigen::Affine3d& T, Curves& out) {
  const long flags = e.integer(70, 0);
  if ((flags & (16 | 64)) != 0) {
    return false;
  }
  std::vector<PolyVertex> v;
  std::vector<Eigen::Vector3d> v3;
  for (const DxfEntity& vertex : e.children) {
    if ((vertex.integer(70, 0) & 16) != 0) {
      continue;  // spline frame control point, not drawn
    }
    const Eigen::Vector3d p = vertex.point(10);
    v.push_back({p.head<2>(), vertex.number(42)});
    v3.push_back(p);
  }
  const bool closed = (flags & 1) != 0;
  if ((flags & 8) != 0) {
    const std::size_t n = v3.size();
    const std::size_t pieces = closed && n >= 2 ? n : (n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < pieces; ++i) {
      if (v3[i] == v3[(i + 1) % n]) {
        continue;
      }
      out.push_back(DrawingLine{world_xy(T, v3[i]), world_xy(T, v3[(i + 1) % n])});
    }
  } else {
    add_polyline(through_ocs(T, e), v, closed, e.point(10).z(), out);
  }
  return true;
}

/// SOLID and TRACE: the outline of corners 1, 2, 4, 3 (DXF stores them in "Z" order).
void solid_curves(const DxfEntity& e, const Eigen::Affine3d& T, Curves& out) {
  const Eigen::Affine3d M = through_ocs(T, e);
  const Eigen::Vector3d c2 = e.point(12);
  const Eigen::Vector3d c3 = e.find(13) != nullptr ? e.point(13) : c2;
  const Eigen::Vector3d ring[] = {e.point(10), e.point(11), c3, c2};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d& a = ring[i];
    const Eigen::Vector3d& b = ring[(i + 1) % 4];
    if (a != b) {
      out.push_back(DrawingLine{world_xy(M, a), world_xy(M, b)});
    }
  }
}

void ellipse_curves(const DxfEntity& e, const Eigen::Affine3d& T, Curves& out) {
  const Eigen::Vector3d center = e.point(10);
  const Eigen::Vector3d major = e.point(11);  // world, relative to the centre
  const Eigen::Vector3d minor = e.number(40, 1.0) * ocs_axes(e.extrusion()).col(2).cross(major);
  const double t0 = e.number(41, 0.0);
  out.push_back(DrawingEllipse{world_xy(T, center), (T.linear() * major).head<2>(),
                               (T.linear() * minor).head<2>(), t0,
                               sweep_end(t0, e.number(42, kTwoPi))});
}

/// The walk over model space and the blocks it references.
class Expander {
 public:
  Expander(const DxfDocument& doc, const LayerFilter& filter, std::size_t max_entities,
           DxfReport& report)
      : doc_(doc), filter_(filter), max_entities_(max_entities), report_(report) {}

  DrawingGeometry run() {
    for (const DxfEntity& e : doc_.entities) {
      if (e.integer(67, 0) == 1) {
        ++report_.paper_space_skipped;
        continue;
      }
      visit(e, Eigen::Affine3d::Identity(), nullptr);
    }
    if (fit_point_splines_ > 0) {
      report_.warnings.push_back(std::to_string(fit_point_splines_) +
                                 " SPLINEs without control points were drawn through their fit "
                                 "points");
    }
    for (const auto& [kind, count] : warning_counts_) {
      if (count > kWarningsPerKind) {
        report_.warnings.push_back("... and " + std::to_string(count - kWarningsPerKind) +
                                   " more warnings: " + kind);
      }
    }
    return std::move(geometry_);
  }

 private:
  void warn(const std::string& kind, const std::string& message) {
    if (++warning_counts_[kind] <= kWarningsPerKind) {
      report_.warnings.push_back(message);
    }
  }

  void visit(const DxfEntity& e, const Eigen::Affine3d& T, const std::string* parent_layer) {
    if (++visited_ > max_entities_) {
      throw InputError("the drawing expands to more than " + std::to_string(max_entities_) +
                           " entities through nested blocks and arrays",
                       {}, e.line, "max_entities");
    }
    const std::string own = e.layer();
    const std::string layer = parent_layer != nullptr && own == "0" ? *parent_layer : own;
    if (kAnnotation.count(e.type) != 0) {
      ++report_.annotation_skipped[e.type];
      if (e.type == "DIMENSION") {
        if (auto stated = dimension_stated_length(e, doc_, T)) {
          geometry_.stated_lengths.push_back(std::move(*stated));
        }
      }
      return;
    }
    if (e.type == "INSERT") {
      expand_insert(e, T, layer);
      return;
    }
    Curves curves;
    if (e.type == "LINE") {
      curves.push_back(DrawingLine{world_xy(T, e.point(10)), world_xy(T, e.point(11))});
    } else if (e.type == "ARC" || e.type == "CIRCLE") {
      if (!(e.number(40) > 0.0)) {
        warn("radius", at_line(e) + " is skipped: its radius " + std::to_string(e.number(40)) +
                           " is not positive");
        ++report_.unsupported_skipped[e.type + " (radius <= 0)"];
        return;
      }
      const double a0 = e.type == "ARC" ? e.number(50) * kDegree : 0.0;
      const double a1 = e.type == "ARC" ? sweep_end(a0, e.number(51) * kDegree) : kTwoPi;
      add_arc(through_ocs(T, e), e.point(10), e.number(40), a0, a1, curves);
    } else if (e.type == "LWPOLYLINE") {
      lwpolyline_curves(e, T, curves);
    } else if (e.type == "POLYLINE") {
      if (!polyline_curves(e, T, curves)) {
        ++report_.unsupported_skipped["POLYLINE (mesh)"];
        return;
      }
    } else if (e.type == "SOLID" || e.type == "TRACE") {
      solid_curves(e, T, curves);
    } else if (e.type == "ELLIPSE") {
      ellipse_curves(e, T, curves);
    } else if (e.type == "SPLINE") {
      if (!spline_curves(e, T, curves)) {
        return;
      }
    } else {
      ++report_.unsupported_skipped[e.type];
      return;
    }
    if (!std::all_of(curves.begin(), curves.end(), [](const Curve& c) { return is_physical(c); })) {
      warn("overflow", at_line(e) + " is skipped: its coordinates are not finite or lie beyond " +
                           "1e10 drawing units (10,000 km in mm) once transformed");
      ++report_.unsupported_skipped[e.type + " (beyond 1e10 units)"];
      return;
    }
    emit(e.type, layer, curves);
  }

  void emit(const std::string& type, const std::string& layer, Curves& curves) {
    auto cached = passes_.find(layer);
    if (cached == passes_.end()) {
      cached = passes_.emplace(layer, layer_passes(filter_, layer)).first;
    }
    const bool kept = cached->second;
    const int index = geometry_.layer_index(layer);
    for (Curve& c : curves) {
      geometry_.items.push_back({std::move(c), index, kept});
    }
    if (kept) {
      ++report_.entities_by_type[type];
      ++report_.entities_by_layer[layer][type];
    } else {
      ++report_.excluded_by_layer_filter;
    }
  }

  /// SPLINE: its B-spline when the control data are consistent, else the polyline through its
  /// fit points. Control and fit points are world coordinates; an affine map keeps a (rational)
  /// B-spline a B-spline of the mapped control points, so they are mapped directly.
  bool spline_curves(const DxfEntity& e, const Eigen::Affine3d& T, Curves& out) {
    BSpline2 spline;
    spline.degree = static_cast<int>(e.integer(71, 3));
    std::vector<Eigen::Vector3d> control, fit;
    for (const DxfGroup& g : e.groups) {
      const int axis = g.code / 10 - 1;  // 10/20/30 and 11/21/31: x, y, z
      if (g.code == 40) {
        spline.knots.push_back(group_double(g));
      }
      if (g.code == 41) {
        spline.weights.push_back(group_double(g));
      }
      if (g.code == 10) {
        control.emplace_back(0.0, 0.0, 0.0);
      }
      if (g.code == 11) {
        fit.emplace_back(0.0, 0.0, 0.0);
      }
      if ((g.code == 10 || g.code == 20 || g.code == 30) && !control.empty()) {
        control.back()(axis) = group_double(g);
      }
      if ((g.code == 11 || g.code == 21 || g.code == 31) && !fit.empty()) {
        fit.back()(axis) = group_double(g);
      }
    }
    for (const Eigen::Vector3d& p : control) {
      spline.control.push_back(world_xy(T, p));
    }
    if (std::all_of(spline.weights.begin(), spline.weights.end(),
                    [](double w) { return w == 1.0; })) {
      spline.weights.clear();
    }
    const std::string problem = control.empty() ? "" : bspline_problem(spline);
    if (!control.empty() && problem.empty()) {
      out.push_back(std::move(spline));
      return true;
    }
    if (fit.size() >= 2) {
      DrawingPolyline line;
      for (const Eigen::Vector3d& p : fit) {
        line.points.push_back(world_xy(T, p));
      }
      if (problem.empty()) {
        ++fit_point_splines_;
      } else {
        warn("SPLINE", at_line(e) + ": " + problem + "; drawn through its fit points");
      }
      out.push_back(std::move(line));
      return true;
    }
    warn("SPLINE",
         at_line(e) + " is skipped: " +
             (problem.empty() ? std::string("it has no control or fit points") : problem));
    ++report_.unsupported_skipped["SPLINE (invalid)"];
    return false;
  }

  void expand_insert(const DxfEntity& e, const Eigen::Affine3d& T, const std::string& layer);

  const DxfDocument& doc_;
  const LayerFilter& filter_;
  std::size_t max_entities_;
  DxfReport& report_;
  DrawingGeometry geometry_;
  std::map<std::string, bool> passes_;
  std::map<std::string, std::size_t> warning_counts_;
  std::vector<std::string> block_stack_;  // upper-case names of the blocks being expanded
  std::set<std::string> warned_blocks_;
  std::size_t visited_ = 0;
  std::size_t fit_point_splines_ = 0;
};

void Expander::expand_insert(const DxfEntity& e, const Eigen::Affine3d& T,
                             const std::string& layer) {
  for (const DxfEntity& child : e.children) {
    ++report_.annotation_skipped[child.type];
  }
  const std::string name = e.text(2);
  const std::string key = upper_ascii(name);
  const DxfBlock* block = doc_.find_block(name);
  if (block == nullptr) {
    if (warned_blocks_.insert(key).second) {
      report_.warnings.push_back(at_line(e) + " places block \"" + name +
                                 "\", which is not defined; skipped");
    }
    return;
  }
  if ((block->flags & 4) != 0 && block->entities.empty() && warned_blocks_.insert(key).second) {
    report_.warnings.push_back("block \"" + name +
                               "\" is an external reference that is not "
                               "bound into this file: its geometry is missing");
  }
  if (std::find(block_stack_.begin(), block_stack_.end(), key) != block_stack_.end() ||
      block_stack_.size() >= kMaxBlockDepth) {
    warn("recursion", at_line(e) + " places block \"" + name + "\" inside itself (or nests " +
                          "deeper than " + std::to_string(kMaxBlockDepth) + "); skipped");
    return;
  }
  ++report_.inserts_expanded;

  const Eigen::Vector3d insertion = e.point(10);  // OCS
  const Eigen::Vector3d scale(e.number(41, 1.0), e.number(42, 1.0), e.number(43, 1.0));
  const Eigen::AngleAxisd rotation(e.number(50) * kDegree, Eigen::Vector3d::UnitZ());
  // MINSERT grid: offsets along the rotated OCS axes, not scaled (as AutoCAD and ezdxf). A zero
  // spacing stacks copies on one spot, so it is drawn once.
  const double column_spacing = e.number(44), row_spacing = e.number(45);
  const long columns = column_spacing == 0.0 ? 1 : std::max(1L, e.integer(70, 1));
  const long rows = row_spacing == 0.0 ? 1 : std::max(1L, e.integer(71, 1));
  if (static_cast<double>(columns) * static_cast<double>(rows) >
      static_cast<double>(max_entities_)) {
    throw InputError("the array of " + std::to_string(rows) + " x " + std::to_string(columns) +
                         " copies is larger than the max_entities limit",
                     {}, e.line, "max_entities");
  }
  const Eigen::Affine3d placed = through_ocs(T, e);
  block_stack_.push_back(key);
  for (long row = 0; row < rows; ++row) {
    for (long column = 0; column < columns; ++column) {
      const Eigen::Vector3d offset =
          rotation * Eigen::Vector3d(column * column_spacing, row * row_spacing, 0.0);
      const Eigen::Affine3d cell = placed * Eigen::Translation3d(insertion + offset) * rotation *
                                   Eigen::Scaling(scale) * Eigen::Translation3d(-block->base);
      for (const DxfEntity& inner : block->entities) {
        visit(inner, cell, &layer);
      }
    }
  }
  block_stack_.pop_back();
}

}  // namespace

DrawingGeometry expand_dxf_entities(const DxfDocument& doc, const LayerFilter& filter,
                                    std::size_t max_entities, DxfReport& report) {
  return Expander(doc, filter, max_entities, report).run();
}

}  // namespace floorgrid::io
