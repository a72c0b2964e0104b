#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace floorgrid::io {

// How report.html writes text and numbers: one place, so that the page reads consistently and
// a test can format a metrics.json value as the page does and find it there.

/// `text` safe inside HTML or XML text and double-quoted attributes (& < > " ' escaped; the
/// report and the GDAL VRT use it).
std::string html_escape(std::string_view text);

/// A length: "0.042 m" (millimetres shown), "12.345 m", or "3.2e-10 m" below a millimetre (the
/// back-and-forth drift), "0.000 m" for zero; "n/a" when not finite.
std::string format_metres(double metres);
/// A metrics.json length (a number, or null: "n/a").
std::string format_metres(const nlohmann::json& metres);

/// Seconds: "0.42 s", "12.3 s", "1234 s".
std::string format_seconds(double seconds);
/// A metrics.json duration (a number, or null: "n/a").
std::string format_seconds(const nlohmann::json& seconds);

/// A share 0 .. 1 as a percentage: "87.5%"; "n/a" for null or not finite.
std::string format_percent(const nlohmann::json& fraction);

/// A count with thin spaces between thousands: "12 345" (U+202F, kept together on a line).
std::string format_count(long long count);
/// A metrics.json count (a number, or null: "n/a").
std::string format_count(const nlohmann::json& count);

/// A plain ratio such as a scale: 4 decimals, "1.0213", or "2.1e-05" below 0.0005 (a scale's
/// spread); "n/a" when not finite or null.
std::string format_ratio(const nlohmann::json& value);

}  // namespace floorgrid::io
