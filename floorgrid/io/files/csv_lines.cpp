#include "floorgrid/io/files/csv_lines.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"

namespace floorgrid::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

}  // namespace

CsvLines::CsvLines(const std::filesystem::path& path)
    : file_(path.string()), text_(read_whole_file(path)), rest_(text_) {
  if (rest_.substr(0, 3) == "\xEF\xBB\xBF")
    rest_.remove_prefix(3);  // UTF-8 byte order mark
}

bool CsvLines::next(std::vector<std::string_view>& fields) {
  while (!rest_.empty()) {
    const std::size_t newline = rest_.find('\n');
    const std::string_view line = trim(rest_.substr(0, newline));
    rest_.remove_prefix(newline == std::string_view::npos ? rest_.size() : newline + 1);
    ++line_;
    if (line.empty() || line.front() == '#')
      continue;
    fields.clear();
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(trim(line.substr(start, comma - start)));
      if (comma == std::string_view::npos)
        break;
      start = comma + 1;
    }
    return true;
  }
  return false;
}

double CsvLines::number(std::string_view field, const std::string& column, double max_abs) const {
  double v = 0.0;
  const char* begin = field.data();
  const char* end = begin + field.size();
  if (begin < end && *begin == '+')
    ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || ptr != end || begin == end)
    throw InputError(fmt::format("not a number: '{}'", field), file_, line_, column);
  if (!std::isfinite(v))
    throw InputError("value must be finite", file_, line_, column);
  if (std::abs(v) > max_abs) {
    throw InputError(fmt::format("{:g} is beyond {:g}: not a physical coordinate", v, max_abs),
                     file_, line_, column);
  }
  return v;
}

}  // namespace floorgrid::io
