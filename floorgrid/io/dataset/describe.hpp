#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/maps/plan_unit_choice.hpp"

namespace floorgrid::io {

/// The kinds of file `floorgrid info` understands.
enum class FileKind { map_yaml, image, dxf, log, pairs, dataset, json };

/// The kind's name as reported ("map", "image", "dxf", "log", "pairs", "dataset", "json").
std::string to_string(FileKind kind);

/// Tells what `path` is by its name and, where the name is ambiguous, its content.
/// Throws InputError when it cannot tell.
FileKind detect_file_kind(const std::filesystem::path& path);

/// A unit a DXF may be in, as `info --json` (`unit_candidates`) and metrics.json
/// (`floorplan_units.candidates`) list it: unit, metres_per_unit, score and probability.
nlohmann::json unit_candidate_json(const PlanUnitCandidate& candidate);

/// Options of describe().
struct DescribeOptions {
  std::optional<double> resolution;  ///< bare images: metres per pixel (else pixels only)
  std::optional<Pose2> origin;       ///< bare images: origin x, y, yaw
};

/// What a map, plan, log, pairs file or dataset holds, as a JSON object with `path`, `kind` and
/// kind-specific fields (sizes, bounds in metres, counts, units, warnings). Reads the file(s);
/// throws InputError on bad input.
nlohmann::json describe(const std::filesystem::path& path, const DescribeOptions& options = {});

}  // namespace floorgrid::io
