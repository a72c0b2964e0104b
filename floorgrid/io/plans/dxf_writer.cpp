#include "floorgrid/io/plans/dxf_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/maps/plan_units.hpp"

namespace floorgrid::io {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

/// Appends DXF groups: the code right-aligned in three columns, as AutoCAD writes it.
class GroupWriter {
 public:
  void text(int code, std::string_view value) { out_ += fmt::format("{:>3}\n{}\n", code, value); }
  void integer(int code, long value) { out_ += fmt::format("{:>3}\n{:>6}\n", code, value); }
  // 17 significant digits identify every double exactly.
  void number(int code, double value) { out_ += fmt::format("{:>3}\n{:.17g}\n", code, value); }
  void point(int x_code, const Eigen::Vector2d& p) {
    number(x_code, p.x());
    number(x_code + 10, p.y());
    number(x_code + 20, 0.0);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

void check_layer_name(const std::string& name) {
  if (name.find_first_of("\r\n") != std::string::npos) {
    throw InputError("a layer name with a line break cannot be written to DXF", {}, 0, "layers");
  }
}

void write_header(GroupWriter& w, int insunits, const Eigen::AlignedBox2d& extent) {
  w.text(0, "SECTION");
  w.text(2, "HEADER");
  w.text(9, "$ACADVER");
  w.text(1, "AC1009");
  w.text(9, "$INSUNITS");
  w.integer(70, insunits);
  w.text(9, "$EXTMIN");
  w.point(10, extent.min());
  w.text(9, "$EXTMAX");
  w.point(10, extent.max());
  w.text(0, "ENDSEC");
}

void write_tables(GroupWriter& w, const std::vector<std::string>& layers) {
  w.text(0, "SECTION");
  w.text(2, "TABLES");
  w.text(0, "TABLE");
  w.text(2, "LTYPE");
  w.integer(70, 1);
  w.text(0, "LTYPE");
  w.text(2, "CONTINUOUS");
  w.integer(70, 0);
  w.text(3, "Solid line");
  w.integer(72, 65);
  w.integer(73, 0);
  w.number(40, 0.0);
  w.text(0, "ENDTAB");
  w.text(0, "TABLE");
  w.text(2, "LAYER");
  w.integer(70, static_cast<long>(layers.size()));
  for (const std::string& layer : layers) {
    w.text(0, "LAYER");
    w.text(2, layer);
    w.integer(70, 0);
    w.integer(62, 7);
    w.text(6, "CONTINUOUS");
  }
  w.text(0, "ENDTAB");
  w.text(0, "ENDSEC");
}

}  // namespace

std::string dxf_text(const VectorFloorplan& plan, const DxfWriteOptions& options) {
  const std::optional<int> insunits = insunits_code(options.header_units);
  if (!insunits) {
    throw InputError(
        "unknown unit \"" + options.header_units + "\" (expected none, m, cm, mm, in or ft)", {}, 0,
        "header_units");
  }
  const double k = options.units_per_metre;
  if (!(k > 0.0) || !std::isfinite(k)) {
    throw InputError("must be a positive number (got " + std::to_string(k) + ")", {}, 0,
                     "units_per_metre");
  }
  // Layer 0 always exists in DXF; the plan's own layers follow it.
  std::vector<std::string> layers{"0"};
  for (const std::string& name : plan.layers()) {
    check_layer_name(name);
    if (!name.empty() && name != "0") {
      layers.push_back(name);
    }
  }
  const auto layer_of = [&](int index) -> std::string_view {
    const std::string& name = plan.layers()[index];
    return name.empty() ? std::string_view("0") : std::string_view(name);
  };

  Eigen::AlignedBox2d extent(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  if (!plan.empty()) {
    const Eigen::AlignedBox2d box = plan.bounds();
    extent = Eigen::AlignedBox2d(box.min() * k, box.max() * k);
  }

  GroupWriter w;
  write_header(w, *insunits, extent);
  write_tables(w, layers);
  w.text(0, "SECTION");
  w.text(2, "ENTITIES");
  for (const Segment& s : plan.segments()) {
    w.text(0, "LINE");
    w.text(8, layer_of(s.layer));
    w.point(10, s.a * k);
    w.point(11, s.b * k);
  }
  for (const Arc& arc : plan.arcs()) {
    const bool full = arc.end_angle - arc.start_angle >= 2.0 * std::numbers::pi;
    w.text(0, full ? "CIRCLE" : "ARC");
    w.text(8, layer_of(arc.layer));
    w.point(10, arc.center * k);
    w.number(40, arc.radius * k);
    if (!full) {
      w.number(50, arc.start_angle * kRadToDeg);
      w.number(51, arc.end_angle * kRadToDeg);
    }
  }
  w.text(0, "ENDSEC");
  w.text(0, "EOF");
  return w.take();
}

void write_dxf(const VectorFloorplan& plan, const std::filesystem::path& path,
               const DxfWriteOptions& options) {
  write_file_atomically(path, dxf_text(plan, options));
}

}  // namespace floorgrid::io
