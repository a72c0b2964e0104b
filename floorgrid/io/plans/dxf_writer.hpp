#pragma once

#include <filesystem>
#include <string>

#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid::io {

/// How a floorplan is written as DXF.
struct DxfWriteOptions {
  /// What the `$INSUNITS` header claims: none | m | cm | mm | in | ft. It need not match
  /// `units_per_metre` (simulating real files whose header lies).
  std::string header_units = "m";
  double units_per_metre = 1.0;  ///< drawing units per metre: coordinates are metres x this; > 0
};

/// Writes `plan` as ASCII DXF R12 (AC1009, which ezdxf, libdime and AutoCAD read): a HEADER with
/// $ACADVER, $INSUNITS, $EXTMIN and $EXTMAX, a LAYER table with every layer of the plan, and its
/// segments as LINE and arcs as ARC (full circles as CIRCLE) in ENTITIES. Numbers are printed to
/// 17 significant digits, so doubles read back exactly. The file is replaced atomically.
/// Throws InputError on bad options or a layer name that cannot be written.
void write_dxf(const VectorFloorplan& plan, const std::filesystem::path& path,
               const DxfWriteOptions& options = {});

/// The DXF text write_dxf() writes.
std::string dxf_text(const VectorFloorplan& plan, const DxfWriteOptions& options = {});

}  // namespace floorgrid::io
