#include "floorgrid/io/plans/dxf_reader.hpp"

#include <string_view>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/plans/dxf_document.hpp"
#include "floorgrid/io/plans/dxf_entities.hpp"
#include "floorgrid/io/plans/dxf_geometry.hpp"
#include "floorgrid/io/plans/dxf_tokens.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/plan_unit_choice.hpp"

namespace floorgrid::io {

namespace {

std::optional<PlanUnit> validate(const DxfReadOptions& options) {
  if (!(options.curve_tolerance > 0.0)) {
    throw InputError("must be > 0 metres (got " + std::to_string(options.curve_tolerance) + ")", {},
                     0, "curve_tolerance");
  }
  if (options.max_entities == 0) {
    throw InputError("must be > 0", {}, 0, "max_entities");
  }
  return parse_units_option(options.units, "units");
}

/// Adds what `$INSUNITS` says to the evidence for choose_plan_unit.
void add_header_units(const DxfDocument& doc, PlanUnitEvidence& evidence) {
  if (const DxfGroup* g = doc.header_value("$INSUNITS", 70)) {
    const long code = group_integer(*g);
    evidence.header_name = insunits_name(static_cast<int>(code));
    evidence.header_unit = plan_unit_from_insunits(static_cast<int>(code));
  }
}

/// `$EXTMIN`/`$EXTMAX` scaled to metres, or an empty box when absent or not a box.
Eigen::AlignedBox2d header_extent(const DxfDocument& doc, double metres_per_unit) {
  const DxfGroup* min_x = doc.header_value("$EXTMIN", 10);
  const DxfGroup* min_y = doc.header_value("$EXTMIN", 20);
  const DxfGroup* max_x = doc.header_value("$EXTMAX", 10);
  const DxfGroup* max_y = doc.header_value("$EXTMAX", 20);
  Eigen::AlignedBox2d box;
  if (min_x && min_y && max_x && max_y) {
    const Eigen::Vector2d lo(group_double(*min_x), group_double(*min_y));
    const Eigen::Vector2d hi(group_double(*max_x), group_double(*max_y));
    // AutoCAD writes +-1e20 for an empty drawing: only a real box counts.
    if ((lo.array() <= hi.array()).all() && (hi - lo).maxCoeff() < 1e15) {
      box.extend(lo * metres_per_unit);
      box.extend(hi * metres_per_unit);
    }
  }
  return box;
}

std::string summary_of_skipped(const DxfReport& report) {
  std::size_t annotation = 0, unsupported = 0;
  for (const auto& [type, n] : report.annotation_skipped) {
    annotation += n;
  }
  for (const auto& [type, n] : report.unsupported_skipped) {
    unsupported += n;
  }
  return std::to_string(annotation) + " annotation and " + std::to_string(unsupported) +
         " unsupported entities skipped, " + std::to_string(report.paper_space_skipped) +
         " in paper space";
}

DxfFloorplan read_document(const std::string& text, const DxfReadOptions& options,
                           std::optional<PlanUnit> requested) {
  const DxfDocument doc = parse_dxf_document(tokenize_dxf(text));
  DxfFloorplan out;
  DxfReport& report = out.report;
  report.warnings = doc.warnings;
  if (const DxfGroup* g = doc.header_value("$ACADVER", 1)) {
    report.version = g->trimmed();
  }

  const LayerFilter filter{options.include_layers, options.exclude_layers};
  const DrawingGeometry geometry = expand_dxf_entities(doc, filter, options.max_entities, report);
  if (geometry.items.empty()) {
    throw InputError("the drawing holds no geometry in model space (" + summary_of_skipped(report) +
                     ")");
  }

  // The unit is a property of the whole drawing: layers the filters drop still tell it (a filter
  // keeping only walls must not lose the door swings that reveal inches).
  PlanUnitEvidence evidence = drawing_unit_evidence(geometry);
  add_header_units(doc, evidence);
  PlanUnitChoice choice = choose_plan_unit(evidence, requested);
  report.header_units = evidence.header_name;
  report.units_used = unit_name(choice.unit);
  report.metres_per_unit = choice.metres_per_unit;
  report.units_reason = choice.reason;
  report.units_source = to_string(choice.source);
  report.units_confidence = to_string(choice.confidence);
  report.units_evidence = std::move(choice.evidence);
  report.unit_candidates = std::move(choice.candidates);
  report.warnings.insert(report.warnings.end(), choice.warnings.begin(), choice.warnings.end());

  out.plan = drawing_to_floorplan(geometry, choice.metres_per_unit, options.curve_tolerance);
  if (out.plan.empty()) {
    throw InputError("the layer filters leave no geometry (" +
                         std::to_string(report.excluded_by_layer_filter) +
                         " geometry entities excluded)",
                     {}, 0, options.include_layers.empty() ? "exclude_layers" : "include_layers");
  }
  report.extent_m = out.plan.bounds();
  report.header_extent_m = header_extent(doc, choice.metres_per_unit);
  return out;
}

}  // namespace

DxfFloorplan read_dxf(const std::filesystem::path& path, const DxfReadOptions& options) {
  const std::optional<PlanUnit> requested = validate(options);
  const std::string text = read_whole_file(path);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError("the file is empty", path.string());
  }
  if (is_binary_dxf(text)) {
    throw InputError(
        "binary DXF is not supported; save as ASCII DXF (AutoCAD: SAVEAS, DXF, "
        "Options, Format ASCII; or convert it, e.g. with ezdxf or the ODA File "
        "Converter)",
        path.string());
  }
  try {
    return read_document(text, options, requested);
  } catch (const InputError& e) {
    // The parsing layers know lines and options but not the file: name it here.
    if (!e.file().empty()) {
      throw;
    }
    throw InputError(e.message(), path.string(), e.line(), e.field());
  }
}

}  // namespace floorgrid::io
