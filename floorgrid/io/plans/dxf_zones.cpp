#include "floorgrid/io/plans/dxf_zones.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/plans/dxf_document.hpp"
#include "floorgrid/io/plans/dxf_tokens.hpp"
#include "floorgrid/maps/layer_filter.hpp"

namespace floorgrid::io {

namespace {

/// Chord error of HATCH arc edges drawn as segments, in drawing units (relative to the radius).
constexpr double kArcSegmentsPerTurn = 72.0;

struct Reader {
  const std::string& where;
  double scale;
  PlanLayers layers;

  Zone new_zone(const DxfEntity& e, const std::string& kind) {
    Zone z;
    z.index = layers.zones.size();
    z.name = fmt::format("{} line {} ({})", kind, e.line, e.layer());
    return z;
  }

  /// The OCS x of entities whose extrusion is (0, 0, -1) is mirrored (the arbitrary-axis
  /// algorithm for that direction); others are taken in the world XY plane.
  Eigen::Vector2d world(const DxfEntity& e, double x, double y) const {
    const double mirror = e.extrusion().z() < 0.0 ? -1.0 : 1.0;
    return Eigen::Vector2d(mirror * x, y) * scale;
  }

  /// A closed polyline's vertices in its OCS (drawing units) and the bulge of the edge leaving
  /// each (tan of a quarter of the arc's angle, positive counter-clockwise).
  struct Bulged {
    std::vector<Eigen::Vector2d> vertices;
    std::vector<double> bulges;
    void add(const Eigen::Vector2d& v) {
      vertices.push_back(v);
      bulges.push_back(0.0);
    }
    void bulge(double b) {
      if (!bulges.empty())
        bulges.back() = b;
    }
  };

  /// The ring in metres, each bulged edge drawn as its arc (kArcSegmentsPerTurn a turn), in the
  /// OCS before the mirror so that the arc keeps its side.
  Ring expand(const DxfEntity& e, const Bulged& b) const {
    Ring out;
    const std::size_t n = b.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& p0 = b.vertices[i];
      out.push_back(world(e, p0.x(), p0.y()));
      const double bulge = b.bulges[i];
      const Eigen::Vector2d& p1 = b.vertices[(i + 1) % n];
      if (bulge == 0.0 || !std::isfinite(bulge) || p0 == p1 || n < 2)
        continue;
      const double theta = 4.0 * std::atan(bulge);
      const Eigen::Vector2d c = p1 - p0;
      const Eigen::Vector2d centre =
          p0 + 0.5 * c + (1.0 - bulge * bulge) / (4.0 * bulge) * Eigen::Vector2d(-c.y(), c.x());
      const double r = (p0 - centre).norm();
      const double a0 = std::atan2(p0.y() - centre.y(), p0.x() - centre.x());
      const int segments = std::max(
          2, static_cast<int>(std::ceil(std::abs(theta) / (2 * M_PI) * kArcSegmentsPerTurn)));
      for (int k = 1; k < segments; ++k) {
        const double a = a0 + theta * k / segments;
        out.push_back(world(e, centre.x() + r * std::cos(a), centre.y() + r * std::sin(a)));
      }
    }
    return out;
  }

  void lwpolyline(const DxfEntity& e) {
    if ((e.integer(70, 0) & 1) == 0)
      open_polyline(e);
    Zone z = new_zone(e, "LWPOLYLINE");
    Bulged ring;
    double x = 0.0;
    bool has_x = false;
    for (const DxfGroup& g : e.groups) {
      if (g.code == 10) {
        x = group_double(g);
        has_x = true;
      } else if (g.code == 20 && has_x) {
        ring.add({x, group_double(g)});
        has_x = false;
      } else if (g.code == 42) {
        ring.bulge(group_double(g));
      }
    }
    z.outer = expand(e, ring);
    add(e, std::move(z));
  }

  void polyline(const DxfEntity& e) {
    const long flags = e.integer(70, 0);
    if (flags & (8 | 16 | 64))
      return;  // 3D polylines and meshes are no zones
    if ((flags & 1) == 0)
      open_polyline(e);
    Zone z = new_zone(e, "POLYLINE");
    Bulged ring;
    for (const DxfEntity& v : e.children) {
      if (upper_ascii(v.type) != "VERTEX")
        continue;
      const Eigen::Vector3d p = v.point(10);
      ring.add({p.x(), p.y()});
      ring.bulge(v.number(42, 0.0));
    }
    z.outer = expand(e, ring);
    add(e, std::move(z));
  }

  [[noreturn]] void open_polyline(const DxfEntity& e) {
    throw InputError(fmt::format("{} on layer '{}' is open (its closed flag, group 70 bit 1, is "
                                 "not set): a zone must be a closed polygon",
                                 e.type, e.layer()),
                     where, e.line, "70");
  }

  void hatch(const DxfEntity& e) {
    const auto& gs = e.groups;
    std::size_t i = 0;
    while (i < gs.size() && gs[i].code != 91)
      ++i;
    if (i == gs.size())
      throw InputError("HATCH without boundary paths (group 91)", where, e.line, "91");
    const long paths = group_integer(gs[i++]);
    Zone z = new_zone(e, "HATCH");
    for (long p = 0; p < paths; ++p) {
      while (i < gs.size() && gs[i].code != 92)
        ++i;
      if (i == gs.size())
        throw InputError("HATCH ends before its boundary path " + std::to_string(p), where, e.line,
                         "92");
      const long type = group_integer(gs[i++]);
      Ring ring;
      if (type & 2) {
        // Polyline path: 72 has-bulge, 73 closed, 93 vertices, then 10/20[/42] each.
        long count = 0;
        while (i < gs.size() && gs[i].code != 93)
          ++i;
        if (i < gs.size())
          count = group_integer(gs[i++]);
        double x = 0.0;
        bool has_x = false;
        Bulged bulged;
        while (i < gs.size() && static_cast<long>(bulged.vertices.size()) < count) {
          const DxfGroup& g = gs[i++];
          if (g.code == 10) {
            x = group_double(g);
            has_x = true;
          } else if (g.code == 20 && has_x) {
            bulged.add({x, group_double(g)});
            has_x = false;
          } else if (g.code == 42) {
            bulged.bulge(group_double(g));
          }
        }
        if (i < gs.size() && gs[i].code == 42)
          bulged.bulge(group_double(gs[i++]));
        ring = expand(e, bulged);
      } else {
        // Edge path: 93 edges, each 72 type: 1 line (10, 20, 11, 21), 2 arc (10, 20 centre,
        // 40 radius, 50 and 51 angles in degrees, 73 counter-clockwise).
        while (i < gs.size() && gs[i].code != 93)
          ++i;
        const long edges = i < gs.size() ? group_integer(gs[i++]) : 0;
        for (long k = 0; k < edges; ++k) {
          while (i < gs.size() && gs[i].code != 72)
            ++i;
          if (i == gs.size())
            throw InputError("HATCH edge path ends early", where, e.line, "72");
          const long edge_type = group_integer(gs[i++]);
          std::map<int, double> v;
          while (i < gs.size() && gs[i].code != 72 && gs[i].code != 97 && gs[i].code != 92) {
            if (gs[i].code >= 10 && gs[i].code <= 73)
              v[gs[i].code] = group_double(gs[i]);
            ++i;
          }
          if (edge_type == 1) {
            ring.push_back(world(e, v[10], v[20]));
          } else if (edge_type == 2) {
            const double r = v[40], a0 = v[50] * M_PI / 180.0, a1 = v[51] * M_PI / 180.0;
            const bool ccw = v.count(73) == 0 || v[73] != 0.0;
            double sweep = ccw ? a1 - a0 : a0 - a1;
            while (sweep <= 0.0)
              sweep += 2 * M_PI;
            const int n =
                std::max(2, static_cast<int>(std::ceil(sweep / (2 * M_PI) * kArcSegmentsPerTurn)));
            for (int s = 0; s < n; ++s) {
              const double a = a0 + (ccw ? 1 : -1) * sweep * s / n;
              ring.push_back(world(e, v[10] + r * std::cos(a), v[20] + r * std::sin(a)));
            }
          } else {
            throw InputError(
                fmt::format("HATCH boundary edge of type {} (ellipse or spline) is not "
                            "read: redraw the zone as a closed polyline",
                            edge_type),
                where, e.line, "72");
          }
        }
      }
      if (!ring.empty() && ring.front() == ring.back())
        ring.pop_back();
      if (p == 0)
        z.outer = std::move(ring);
      else
        z.holes.push_back(std::move(ring));
    }
    add(e, std::move(z));
  }

  void add(const DxfEntity& e, Zone z) {
    if (z.outer.size() > 1 && z.outer.front() == z.outer.back())
      z.outer.pop_back();
    try {
      validate_zone(z, where);
    } catch (const InputError& error) {
      throw InputError(error.message(), where, e.line, error.field());
    }
    layers.zones.push_back(std::move(z));
  }
};

}  // namespace

PlanLayers read_dxf_zones(std::string_view text, const std::string& where, const std::string& layer,
                          double metres_per_unit) {
  if (is_binary_dxf(text))
    throw InputError("binary DXF is not read: save it as ASCII DXF", where, 0, "");
  DxfDocument doc;
  try {
    doc = parse_dxf_document(tokenize_dxf(text));
  } catch (const InputError& e) {
    throw InputError(e.message(), where, e.line(), e.field());
  }
  Reader reader{where, metres_per_unit, {}};
  std::set<std::string> seen(doc.layer_table.begin(), doc.layer_table.end());
  for (const DxfEntity& e : doc.entities) {
    const std::string entity_layer = e.layer();
    seen.insert(entity_layer);
    if (!layer_matches(layer, entity_layer) || e.integer(67, 0) == 1)
      continue;  // another layer, or paper space
    const std::string type = upper_ascii(e.type);
    if (type == "LWPOLYLINE")
      reader.lwpolyline(e);
    else if (type == "POLYLINE")
      reader.polyline(e);
    else if (type == "HATCH")
      reader.hatch(e);
  }
  if (reader.layers.zones.empty()) {
    std::string names;
    for (const std::string& n : seen)
      names += (names.empty() ? "" : ", ") + n;
    bool matched = false;
    for (const std::string& n : seen)
      matched = matched || layer_matches(layer, n);
    throw InputError(matched ? fmt::format("layer '{}' holds no closed LWPOLYLINE, POLYLINE or "
                                           "HATCH (layers in the file: {})",
                                           layer, names)
                             : fmt::format("no layer matches '{}'; the file has: {}", layer, names),
                     where, 0, "--layer");
  }
  return reader.layers;
}

PlanLayers read_dxf_zones_file(const std::filesystem::path& path, const std::string& layer,
                               double metres_per_unit) {
  return read_dxf_zones(read_whole_file(path), path.string(), layer, metres_per_unit);
}

}  // namespace floorgrid::io
