#include "floorgrid/io/plans/dxf_tokens.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) {
    s.remove_prefix(1);
  }
  while (!s.empty() && blank(s.back())) {
    s.remove_suffix(1);
  }
  return s;
}

/// Shows a value in a message without flooding it with garbage bytes.
std::string in_quotes(std::string_view value) {
  std::string out = "\"";
  for (const char c : value.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 0x20 && u < 0x7f) ? c : '?';
  }
  if (value.size() > 40) {
    out += "...";
  }
  return out + "\"";
}

bool parse_double(std::string_view text, double& out) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
  }
  if (text.empty()) {
    return false;
  }
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(out);
}

/// Reads one line starting at `pos`; moves `pos` past its line ending.
std::string_view next_line(std::string_view text, std::size_t& pos) {
  const std::size_t end = text.find('\n', pos);
  std::string_view line = text.substr(pos, end == std::string_view::npos ? text.npos : end - pos);
  pos = end == std::string_view::npos ? text.size() : end + 1;
  if (!line.empty() && line.back() == '\r') {
    line.remove_suffix(1);
  }
  return line;
}

}  // namespace

std::string_view DxfGroup::trimmed() const {
  return trim(value);
}

bool is_binary_dxf(std::string_view bytes) {
  // The sentinel's first 18 characters suffice: a truncated sentinel is still binary DXF.
  return bytes.substr(0, 18) == kBinaryDxfSentinel.substr(0, 18);
}

std::vector<DxfGroup> tokenize_dxf(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") {
    text.remove_prefix(3);
  }
  std::vector<DxfGroup> groups;
  std::size_t pos = 0;
  long line = 0;
  while (pos < text.size()) {
    const std::string_view code_line = next_line(text, pos);
    ++line;
    const std::string_view code_text = trim(code_line);
    // Blank lines after the last group (an extra newline at the end) are not a group.
    if (code_text.empty() && trim(text.substr(pos)).empty()) {
      break;
    }
    DxfGroup group;
    group.line = line;
    const auto [end, ec] =
        std::from_chars(code_text.data(), code_text.data() + code_text.size(), group.code);
    if (code_text.empty() || ec != std::errc() || end != code_text.data() + code_text.size()) {
      throw InputError("expected a DXF group code (an integer), got " + in_quotes(code_line), {},
                       line);
    }
    if (pos >= text.size()) {
      throw InputError(
          "group code " + std::to_string(group.code) + " has no value line: the file is truncated",
          {}, line);
    }
    group.value = std::string(next_line(text, pos));
    ++line;
    groups.push_back(std::move(group));
    if (groups.back().code == 0 && groups.back().trimmed() == "EOF") {
      break;
    }
  }
  return groups;
}

double group_double(const DxfGroup& group) {
  double value = 0.0;
  if (!parse_double(group.value, value)) {
    throw InputError("group code " + std::to_string(group.code) + " needs a number, got " +
                         in_quotes(group.value),
                     {}, group.line + 1);
  }
  return value;
}

long group_integer(const DxfGroup& group) {
  double value = 0.0;
  if (!parse_double(group.value, value) || value != std::floor(value) ||
      std::abs(value) > static_cast<double>(std::numeric_limits<int>::max())) {
    throw InputError("group code " + std::to_string(group.code) + " needs an integer, got " +
                         in_quotes(group.value),
                     {}, group.line + 1);
  }
  return static_cast<long>(value);
}

}  // namespace floorgrid::io
