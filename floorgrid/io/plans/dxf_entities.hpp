#pragma once

#include <cstddef>

#include "floorgrid/io/plans/dxf_document.hpp"
#include "floorgrid/io/plans/dxf_geometry.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/maps/layer_filter.hpp"

namespace floorgrid::io {

/// Expands the model space of `doc` into world-XY curves in drawing units: every entity through
/// its object coordinate system and the transforms of the INSERTs placing it (nested blocks,
/// MINSERT arrays), block contents on layer `0` taking the placing INSERT's layer. Items on
/// layers that `filter` drops are kept with `kept = false`. Fills the counts and warnings of
/// `report`. Throws InputError (line set) on malformed numbers and when the expansion would
/// visit more than `max_entities` entities.
DrawingGeometry expand_dxf_entities(const DxfDocument& doc, const LayerFilter& filter,
                                    std::size_t max_entities, DxfReport& report);

}  // namespace floorgrid::io
