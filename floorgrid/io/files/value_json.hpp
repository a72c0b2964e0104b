#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "floorgrid/core/value.hpp"

namespace floorgrid::io {

/// Nesting of arrays and objects a JSON file may have at most (model files nest about 6 deep):
/// deeper files are refused before parsing, so that no file can exhaust the stack.
inline constexpr int kMaxJsonDepth = 64;

/// A value tree as JSON (non-finite numbers become null, as JSON has none).
nlohmann::json to_json(const Value& value);

/// A JSON document as a value tree.
Value from_json(const nlohmann::json& json);

/// Parses JSON text strictly; InputError naming `where` and the line for text that is not JSON,
/// nested deeper than kMaxJsonDepth, holding a number out of range (1e999), or an object with a
/// key given twice (JSON parsers disagree on which one counts: `"unit"` twice would change the
/// mapping silently).
nlohmann::json parse_json_document(const std::string& text, const std::string& where);

/// parse_json_document as a value tree.
Value parse_json(const std::string& text, const std::string& where);

/// A value tree as JSON text, indented by `indent` spaces per level.
std::string dump_json(const Value& value, int indent = 1);

}  // namespace floorgrid::io
