#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "floorgrid/maps/plan_layers.hpp"

namespace floorgrid::io {

/// Zones drawn in a DXF: every closed LWPOLYLINE, closed POLYLINE (2D, VERTEX/SEQEND) and HATCH
/// boundary (polyline and line-edge paths; the first path the outer ring, the others holes) in
/// the ENTITIES section on the layers matching `layer` (a case-insensitive glob, matched after
/// any bound-xref prefix as the plan's layer filters are). Bulged edges become their arcs
/// (72 segments a turn). Coordinates x metres_per_unit. InputError naming the file and the line for
/// an open polyline, and listing the layers the file has when none matches `layer`.
PlanLayers read_dxf_zones(std::string_view text, const std::string& where, const std::string& layer,
                          double metres_per_unit = 1.0);

/// read_dxf_zones of a file.
PlanLayers read_dxf_zones_file(const std::filesystem::path& path, const std::string& layer,
                               double metres_per_unit = 1.0);

}  // namespace floorgrid::io
