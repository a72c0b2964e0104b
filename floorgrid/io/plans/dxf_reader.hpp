#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "floorgrid/maps/plan_unit_choice.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid::io {

/// How a DXF floorplan is read. Defaults in one place (STYLE habit 3).
struct DxfReadOptions {
  std::string units = "auto";  ///< auto | m | cm | mm | in | ft: drawing unit (auto: inferred)
  std::vector<std::string> include_layers;  ///< globs (case-insensitive); empty keeps all layers
  std::vector<std::string> exclude_layers;  ///< globs dropped after the include filter
  double curve_tolerance = 0.01;  ///< metres: chord error of ELLIPSE, SPLINE and non-uniformly
                                  ///< scaled arcs turned into segments; > 0
  std::size_t max_entities = 5'000'000;  ///< refuse drawings whose nested blocks and arrays
                                         ///< expand to more entities (memory guard, ~100 B each)
};

/// What a DXF file held and how it was read.
struct DxfReport {
  std::string version;           ///< `$ACADVER` (AC1009 = R12, AC1015 = R2000, ...), or empty
  std::string header_units;      ///< what `$INSUNITS` says ("mm", "in", ...), or "none"
  std::string units_used;        ///< the unit applied: m, cm, mm, in or ft
  double metres_per_unit = 1.0;  ///< of units_used
  std::string units_reason;      ///< why units_used was chosen
  /// Where units_used came from: requested, header (`$INSUNITS` kept), header_overruled (the
  /// drawing contradicted it strongly), guessed (no usable header) or run (the robot's map fitted
  /// the plan clearly better in another plausible unit; set by load_dataset).
  std::string units_source;
  std::string units_confidence;  ///< how sure units_used is: high, medium or low
  /// What the drawing shows about its units, one line per kind of evidence (extent, door swings,
  /// dimension texts, walls), each with what it means in the units worth comparing.
  std::vector<std::string> units_evidence;
  /// Units the drawing may be in, with their score and probability, most probable first (those
  /// of at least 1%, and units_used): what a robot's run may decide between.
  std::vector<PlanUnitCandidate> unit_candidates;
  std::vector<std::string> warnings;  ///< everything odd that did not stop reading
  /// Geometry entities kept, by DXF type, counted once per block reference that placed them.
  std::map<std::string, std::size_t> entities_by_type;
  /// Geometry entities kept: layer (after layer-0 inheritance) -> DXF type -> count.
  std::map<std::string, std::map<std::string, std::size_t>> entities_by_layer;
  /// Annotation skipped by type: TEXT, MTEXT, ATTRIB, ATTDEF, DIMENSION, LEADER, MULTILEADER,
  /// HATCH, POINT, VIEWPORT, ...
  std::map<std::string, std::size_t> annotation_skipped;
  std::map<std::string, std::size_t> unsupported_skipped;  ///< other entities skipped, by type
  std::size_t excluded_by_layer_filter = 0;  ///< geometry entities dropped by the layer filters
  std::size_t paper_space_skipped = 0;       ///< entities of the ENTITIES section in paper space
  std::size_t inserts_expanded = 0;  ///< INSERT entities expanded (nested ones per placement)
  Eigen::AlignedBox2d extent_m;      ///< bounds of the plan read, metres
  /// `$EXTMIN`/`$EXTMAX` in metres (the extent AutoCAD saved, annotation included); empty when
  /// the header has none
  Eigen::AlignedBox2d header_extent_m;
};

/// A floorplan read from DXF.
struct DxfFloorplan {
  VectorFloorplan plan;  ///< the drawing's own frame, in metres (drawing units x metres_per_unit)
  DxfReport report;      ///< what was read and how
};

/// Reads an ASCII DXF floorplan: LINE, LWPOLYLINE and POLYLINE (bulges become arcs), ARC, CIRCLE,
/// ELLIPSE and SPLINE (as segments), SOLID and TRACE outlines, and INSERT (nested blocks,
/// MINSERT arrays, rotation, any scales, block base points), each through its object coordinate
/// system, projected onto the world XY plane. Block contents on layer `0` take the layer of
/// the INSERT placing them. Circular arcs stay arcs unless a non-uniform scale makes them
/// elliptical. Annotation is skipped and counted; paper-space entities are skipped.
/// The unit is options.units, or inferred from the drawing and `$INSUNITS` (choose_plan_unit).
/// Throws InputError naming the file and line, or the option, on: a missing, empty, binary,
/// malformed or truncated file; a bad option; a drawing without geometry; layer filters that
/// leave nothing.
DxfFloorplan read_dxf(const std::filesystem::path& path, const DxfReadOptions& options = {});

}  // namespace floorgrid::io
