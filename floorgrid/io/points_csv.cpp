#include "floorgrid/io/points_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"

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

PointsTable read_points_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = read_whole_file(path);
  std::string_view rest(text);
  if (rest.substr(0, 3) == "\xEF\xBB\xBF")
    rest.remove_prefix(3);
  static const char* kNames[] = {"x", "y", "theta"};
  std::size_t columns = 0;
  std::vector<double> values;
  long line_number = 0;
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string_view line = trim(rest.substr(0, newline));
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    ++line_number;
    if (line.empty() || line.front() == '#')
      continue;
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(trim(line.substr(start, comma - start)));
      if (comma == std::string_view::npos)
        break;
      start = comma + 1;
    }
    if (columns == 0) {
      if ((fields.size() != 2 && fields.size() != 3) || fields[0] != "x" || fields[1] != "y" ||
          (fields.size() == 3 && fields[2] != "theta")) {
        throw InputError("header must be x,y or x,y,theta", file, line_number);
      }
      columns = fields.size();
      continue;
    }
    if (fields.size() != columns) {
      throw InputError(fmt::format("expected {} values, got {}", columns, fields.size()), file,
                       line_number);
    }
    for (std::size_t c = 0; c < columns; ++c) {
      double v = 0.0;
      const char* begin = fields[c].data();
      const char* end = begin + fields[c].size();
      if (begin < end && *begin == '+')
        ++begin;
      const auto [ptr, ec] = std::from_chars(begin, end, v);
      if (ec != std::errc() || ptr != end || begin == end || !std::isfinite(v)) {
        throw InputError(fmt::format("not a finite number: '{}'", fields[c]), file, line_number,
                         kNames[c]);
      }
      values.push_back(v);
    }
  }
  if (columns == 0)
    throw InputError("empty file: expected a header x,y or x,y,theta", file);
  const auto n = static_cast<Eigen::Index>(values.size() / columns);
  PointsTable table;
  table.points.resize(2, n);
  if (columns == 3)
    table.headings.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* row = values.data() + static_cast<std::size_t>(i) * columns;
    table.points.col(i) << row[0], row[1];
    if (columns == 3)
      table.headings[i] = row[2];
  }
  return table;
}

void write_mapped_csv(const std::vector<MappedRow>& rows, bool with_headings,
                      const std::filesystem::path& path) {
  std::string out =
      with_headings ? "x,y,theta,std_m,nearest_pair_m,flag\n" : "x,y,std_m,nearest_pair_m,flag\n";
  for (const MappedRow& r : rows) {
    const bool ok = r.mapped.flag != MapFlag::not_invertible;
    if (ok) {
      fmt::format_to(std::back_inserter(out), "{},{}", r.mapped.point.x(), r.mapped.point.y());
    } else {
      out += ",";
    }
    if (with_headings) {
      out += ",";
      if (ok && r.heading)
        fmt::format_to(std::back_inserter(out), "{}", *r.heading);
    }
    out += ",";
    if (r.mapped.std_m)
      fmt::format_to(std::back_inserter(out), "{}", *r.mapped.std_m);
    fmt::format_to(std::back_inserter(out), ",{},{}\n", r.mapped.nearest_pair_m,
                   to_string(r.mapped.flag));
  }
  write_file_atomically(path, out);
}

}  // namespace floorgrid::io
