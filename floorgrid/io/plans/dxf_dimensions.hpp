#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>

#include "floorgrid/io/plans/dxf_document.hpp"
#include "floorgrid/maps/plan_unit_features.hpp"

namespace floorgrid::io {

/// The plain text of a TEXT or MTEXT value: MTEXT formatting codes (`\A1;`, `\H2.5x;`, `\P`,
/// `{...}`, stacked fractions `\S1/2;` as " 1/2") and `%%` control codes removed.
std::string plain_dxf_text(std::string_view text);

/// The length a dimension text states with its unit, in metres: feet and inches (`12'-6"`,
/// `3'-1 1/2"` or `1#2` as old AutoCAD stacks it, `7"`, `16'`, `1/2"`) or metric with a unit (`3.60
/// m`, `360cm`, `3600 mm`, a decimal comma allowed). The first such length in the text counts; a
/// bare number, whose unit is the drawing's own, tells nothing and gives nullopt.
std::optional<double> stated_length_m(std::string_view plain_text);

/// What a linear, aligned, radial or diameter DIMENSION placed by `T` (the transform of the
/// INSERTs around it) states, as unit evidence; nullopt for other dimensions, texts stating no
/// length, and malformed numbers (annotation is no geometry: it never stops reading). The text is
/// the override (group 1) unless that is empty or holds `<>`, else the first TEXT or MTEXT stating
/// a length in the block AutoCAD drew for the dimension (group 2). The measurement is group 42
/// times the scale of `T`, or, where a writer left 42 out, the distance between the definition
/// points mapped by `T` (13 to 14 along the rotation 50, or 10 to 15 for radius and diameter).
std::optional<StatedLength> dimension_stated_length(const DxfEntity& e, const DxfDocument& doc,
                                                    const Eigen::Affine3d& T);

}  // namespace floorgrid::io
