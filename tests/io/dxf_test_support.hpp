#pragma once

// Helpers shared by the DXF tests: hand-written DXF text, and ezdxf (tests/io/ezdxf_dump.py, run
// by Debian's /usr/bin/python3) as an independent reader to compare against.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::test {

/// DXF groups from lines "CODE VALUE" (the value may be empty or hold spaces): one line of
/// DXF text per code and per value, as written by hand.
inline std::string groups(std::string_view pairs) {
  std::string out;
  std::istringstream in{std::string(pairs)};
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t start = line.find_first_not_of(' ');
    if (start == std::string::npos) {
      continue;
    }
    const std::size_t space = line.find(' ', start);
    out += line.substr(start, space - start) + "\n";
    out += (space == std::string::npos ? std::string() : line.substr(space + 1)) + "\n";
  }
  return out;
}

/// A whole DXF file around entity, block and header groups (all as for groups()).
inline std::string dxf_file(std::string_view entities, std::string_view blocks = {},
                            std::string_view header = {}) {
  std::string out;
  if (!header.empty()) {
    out += groups("0 SECTION\n2 HEADER\n") + groups(header) + groups("0 ENDSEC");
  }
  if (!blocks.empty()) {
    out += groups("0 SECTION\n2 BLOCKS\n") + groups(blocks) + groups("0 ENDSEC");
  }
  out += groups("0 SECTION\n2 ENTITIES\n") + groups(entities) + groups("0 ENDSEC\n0 EOF");
  return out;
}

/// The 1-based line of the group code whose value line is the first `value` line in `text`.
inline long line_of(const std::string& text, const std::string& value) {
  std::istringstream in(text);
  std::string line;
  for (long n = 1; std::getline(in, line); ++n) {
    if (line == value) {
      return n - 1;
    }
  }
  return 0;
}

/// Options reading in metres (geometry tests do not depend on unit inference).
inline io::DxfReadOptions metres() {
  io::DxfReadOptions options;
  options.units = "m";
  return options;
}

/// Writes `text` as `name` in `dir` and returns its path.
inline std::filesystem::path put(const TempDir& dir, const std::string& text,
                                 const std::string& name = "plan.dxf") {
  const std::filesystem::path path = dir / name;
  write_file(path, text);
  return path;
}

/// Whether ezdxf can be imported by Debian's python (the `python3` on PATH may lack it).
inline bool ezdxf_available() {
  static const bool available = run_command("/usr/bin/python3 -c 'import ezdxf'").status == 0;
  return available;
}

#define FLOORGRID_REQUIRE_EZDXF()                                                \
  do {                                                                           \
    if (!::floorgrid::test::ezdxf_available()) {                                 \
      GTEST_SKIP() << "ezdxf missing: /usr/bin/python3 -c 'import ezdxf' fails " \
                      "(install python3-ezdxf)";                                 \
    }                                                                            \
  } while (0)

/// What ezdxf reads from `path` (see tests/io/ezdxf_dump.py for the format).
inline nlohmann::json ezdxf_dump(const std::filesystem::path& path, bool explode,
                                 double flatten = 1e-4) {
  const std::string command =
      "/usr/bin/python3 '" FLOORGRID_SOURCE_DIR "/tests/io/ezdxf_dump.py' '" + path.string() + "'" +
      (explode ? " --explode" : "") + " --flatten " + std::to_string(flatten);
  const CommandResult result = run_command(command);
  if (result.status != 0) {
    ADD_FAILURE() << "ezdxf could not read " << path << ":\n" << result.err;
    return {{"entities", nlohmann::json::array()},
            {"counts", nlohmann::json::object()},
            {"counts_by_layer", nlohmann::json::object()}};
  }
  return nlohmann::json::parse(result.out);
}

inline Eigen::Vector2d vec(const nlohmann::json& xy, double scale = 1.0) {
  return Eigen::Vector2d(xy.at(0).get<double>(), xy.at(1).get<double>()) * scale;
}

/// Distance from `p` to the nearest segment of `plan` on `layer`.
inline double distance_to_layer_segments(const VectorFloorplan& plan, const Eigen::Vector2d& p,
                                         const std::string& layer) {
  double best = HUGE_VAL;
  for (const Segment& s : plan.segments()) {
    if (plan.layers()[s.layer] != layer) {
      continue;
    }
    const Eigen::Vector2d d = s.b - s.a;
    const double t =
        d.squaredNorm() > 0.0 ? std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (s.a + t * d)).norm());
  }
  return best;
}

/// Distance from `p` to the polyline through `points` (JSON [x, y] pairs times `scale`).
inline double distance_to_polyline(const Eigen::Vector2d& p, const nlohmann::json& points,
                                   double scale) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Eigen::Vector2d a = vec(points[i], scale), b = vec(points[i + 1], scale);
    const Eigen::Vector2d d = b - a;
    const double t =
        d.squaredNorm() > 0.0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (a + t * d)).norm());
  }
  return best;
}

/// Checks that `plan` holds exactly the geometry ezdxf exploded (`dump`, drawing units times
/// `scale` = metres): every ezdxf LINE, ARC and CIRCLE matched one to one by layer and
/// coordinates within `tol` metres (arc end points as a set, since a mirror swaps them); every
/// point of ezdxf's flattened curves within `curve_tol` of the plan's segments on its layer; and
/// every plan segment left over lying, both ends, within `curve_tol` of such a flattened curve.
inline void expect_same_geometry(const VectorFloorplan& plan, const nlohmann::json& dump,
                                 double scale, double tol, double curve_tol = 0.0) {
  std::vector<bool> used_segment(plan.segments().size(), false);
  std::vector<bool> used_arc(plan.arcs().size(), false);
  std::size_t arcs = 0, missing = 0;
  std::vector<const nlohmann::json*> curves;
  const auto near = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - b).norm() <= tol;
  };
  for (const nlohmann::json& e : dump.at("entities")) {
    const std::string type = e.at("type");
    const std::string layer = e.at("layer");
    bool found = false;
    if (type == "LINE") {
      const Eigen::Vector2d a = vec(e.at("start"), scale), b = vec(e.at("end"), scale);
      // ezdxf splits polylines with repeated vertices into zero-length LINEs; the reader drops
      // those pieces (they draw nothing), so only LINE entities of zero length must match.
      if (a == b && e.at("source") != "LINE") {
        continue;
      }
      for (std::size_t i = 0; i < plan.segments().size() && !found; ++i) {
        const Segment& s = plan.segments()[i];
        if (used_segment[i] || plan.layers()[s.layer] != layer) {
          continue;
        }
        if ((near(s.a, a) && near(s.b, b)) || (near(s.a, b) && near(s.b, a))) {
          used_segment[i] = found = true;
        }
      }
    } else if (type == "ARC" || type == "CIRCLE") {
      ++arcs;
      const Eigen::Vector2d c = vec(e.at("center"), scale);
      const double r = e.at("radius").get<double>() * scale;
      for (std::size_t i = 0; i < plan.arcs().size() && !found; ++i) {
        const Arc& arc = plan.arcs()[i];
        if (used_arc[i] || plan.layers()[arc.layer] != layer) {
          continue;
        }
        if (!near(arc.center, c) || std::abs(arc.radius - r) > tol) {
          continue;
        }
        const double sweep_deg = (arc.end_angle - arc.start_angle) * 180.0 / std::numbers::pi;
        if (type == "CIRCLE") {
          found = std::abs(sweep_deg - 360.0) < 1e-9;
        } else {
          const Eigen::Vector2d s = vec(e.at("start"), scale), t = vec(e.at("end"), scale);
          const Eigen::Vector2d p = arc.point_at(arc.start_angle), q = arc.point_at(arc.end_angle);
          found = std::abs(sweep_deg - e.at("sweep").get<double>()) < 1e-6 &&
                  ((near(p, s) && near(q, t)) || (near(p, t) && near(q, s)));
        }
        if (found) {
          used_arc[i] = true;
        }
      }
    } else {
      for (const nlohmann::json& point : e.at("points")) {
        EXPECT_LE(distance_to_layer_segments(plan, vec(point, scale), layer), curve_tol)
            << e.at("source") << " point " << point << " on layer " << layer;
      }
      curves.push_back(&e);
      found = true;
    }
    if (!found && ++missing <= 10) {
      ADD_FAILURE() << "no match in the plan for ezdxf's " << e;
    }
  }
  EXPECT_EQ(missing, 0u);
  EXPECT_EQ(arcs, plan.arcs().size());
  std::size_t stray = 0;
  for (std::size_t i = 0; i < plan.segments().size(); ++i) {
    if (used_segment[i]) {
      continue;
    }
    const Segment& s = plan.segments()[i];
    const auto on_a_curve = [&](const Eigen::Vector2d& p) {
      return std::any_of(curves.begin(), curves.end(), [&](const nlohmann::json* c) {
        return c->at("layer") == plan.layers()[s.layer] &&
               distance_to_polyline(p, c->at("points"), scale) <= curve_tol;
      });
    };
    if (!on_a_curve(s.a) || !on_a_curve(s.b)) {
      if (++stray <= 10) {
        ADD_FAILURE() << "plan segment (" << s.a.transpose() << ")-(" << s.b.transpose() << ") on "
                      << plan.layers()[s.layer] << " is not in ezdxf's geometry";
      }
    }
  }
  EXPECT_EQ(stray, 0u);
}

/// Checks the report's counts by type and by layer against ezdxf's.
inline void expect_same_counts(const io::DxfReport& report, const nlohmann::json& dump) {
  std::map<std::string, std::size_t> by_type;
  for (const auto& [type, n] : dump.at("counts").items()) {
    by_type[type] = n.get<std::size_t>();
  }
  EXPECT_EQ(report.entities_by_type, by_type);
  std::map<std::string, std::map<std::string, std::size_t>> by_layer;
  for (const auto& [layer, types] : dump.at("counts_by_layer").items()) {
    for (const auto& [type, n] : types.items()) {
      by_layer[layer][type] = n.get<std::size_t>();
    }
  }
  EXPECT_EQ(report.entities_by_layer, by_layer);
}

}  // namespace floorgrid::test
