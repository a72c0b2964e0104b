#include "floorgrid/io/report/report_format.hpp"

#include <fmt/format.h>

#include <cmath>

namespace floorgrid::io {

namespace {

bool finite_number(const nlohmann::json& value) {
  return value.is_number() && std::isfinite(value.get<double>());
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string format_metres(double metres) {
  if (!std::isfinite(metres))
    return "n/a";
  if (metres == 0.0)
    return "0.000 m";
  // Below a millimetre only the magnitude matters (round-trip drift of 1e-10 m is not "0.000").
  if (std::abs(metres) < 0.0005)
    return fmt::format("{:.1e} m", metres);
  return fmt::format("{:.3f} m", metres);
}

std::string format_metres(const nlohmann::json& metres) {
  return finite_number(metres) ? format_metres(metres.get<double>()) : "n/a";
}

std::string format_seconds(double seconds) {
  if (!std::isfinite(seconds))
    return "n/a";
  if (std::abs(seconds) < 10.0)
    return fmt::format("{:.2f} s", seconds);
  if (std::abs(seconds) < 1000.0)
    return fmt::format("{:.1f} s", seconds);
  return fmt::format("{:.0f} s", seconds);
}

std::string format_seconds(const nlohmann::json& seconds) {
  return finite_number(seconds) ? format_seconds(seconds.get<double>()) : "n/a";
}

std::string format_percent(const nlohmann::json& fraction) {
  return finite_number(fraction) ? fmt::format("{:.1f}%", 100.0 * fraction.get<double>()) : "n/a";
}

std::string format_count(long long count) {
  const std::string digits = std::to_string(count < 0 ? -count : count);
  std::string out = count < 0 ? "-" : "";
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0)
      out += "\u202f";
    out += digits[i];
  }
  return out;
}

std::string format_count(const nlohmann::json& count) {
  return count.is_number() ? format_count(count.get<long long>()) : "n/a";
}

std::string format_ratio(const nlohmann::json& value) {
  if (!finite_number(value))
    return "n/a";
  const double v = value.get<double>();
  // A spread of a well-fixed scale is far below 1e-4: its magnitude, not "0.0000".
  if (v != 0.0 && std::abs(v) < 0.0005)
    return fmt::format("{:.1e}", v);
  return fmt::format("{:.4f}", v);
}

}  // namespace floorgrid::io
