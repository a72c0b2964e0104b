#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace floorgrid {

/// Which CAD layers a floorplan keeps. Patterns are case-insensitive globs (`*` any run of
/// characters, `?` any one character).
struct LayerFilter {
  std::vector<std::string> include;  ///< keep only layers matching one of these; empty keeps all
  std::vector<std::string> exclude;  ///< then drop layers matching any of these
};

/// The layer name without an external-reference prefix: bound xrefs name their layers
/// `<xref>$<n>$<layer>` (`xref-Plan$0$A-WALL` gives `A-WALL`), attached ones `<xref>|<layer>`.
/// Nested prefixes are all removed; a name without a prefix is returned unchanged.
std::string_view strip_xref_prefix(std::string_view layer);

/// Whether `text` matches the glob `pattern` as a whole, ignoring ASCII case.
bool glob_match(std::string_view pattern, std::string_view text);

/// Whether a pattern matches a layer: it is tried on the name after strip_xref_prefix() and on
/// the full name (so `xref-Plan*` can select a whole xref).
bool layer_matches(std::string_view pattern, std::string_view layer);

/// Whether `filter` keeps `layer`: it matches an include pattern (or there are none) and no
/// exclude pattern.
bool layer_passes(const LayerFilter& filter, std::string_view layer);

}  // namespace floorgrid

#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// The part of `plan` on the layers `filter` keeps.
VectorFloorplan filter_layers(const VectorFloorplan& plan, const LayerFilter& filter);

}  // namespace floorgrid
