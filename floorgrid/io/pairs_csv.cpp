#include "floorgrid/io/pairs_csv.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"

namespace floorgrid::io {

namespace {

constexpr std::array<std::string_view, 5> kColumns = {"plan_x", "plan_y", "grid_x", "grid_y",
                                                      "weight"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos)
      break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

ReferencePairs read_pairs_csv(const std::filesystem::path& path, double unit) {
  const std::string file = path.string();
  if (!(unit > 0.0) || !std::isfinite(unit)) {
    throw InputError(fmt::format("must be a positive number of metres per unit (got {})", unit),
                     file, 0, "unit");
  }
  std::string text = read_whole_file(path);
  std::string_view rest(text);
  if (rest.substr(0, 3) == "\xEF\xBB\xBF")
    rest.remove_prefix(3);  // UTF-8 byte order mark

  std::vector<double> values;
  std::size_t columns = 0;
  long line_number = 0;
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string_view line = trim(rest.substr(0, newline));
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    ++line_number;
    if (line.empty() || line.front() == '#')
      continue;
    const auto fields = split(line);
    if (columns == 0) {
      if (fields.size() < 4 || fields.size() > 5) {
        throw InputError("header must be plan_x,plan_y,grid_x,grid_y[,weight]", file, line_number);
      }
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c] != kColumns[c]) {
          throw InputError(fmt::format("header column {} must be '{}' (got '{}'); expected "
                                       "plan_x,plan_y,grid_x,grid_y[,weight]",
                                       c + 1, kColumns[c], fields[c]),
                           file, line_number);
        }
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
      if (ec != std::errc() || ptr != end || begin == end) {
        throw InputError(fmt::format("not a number: '{}'", fields[c]), file, line_number,
                         std::string(kColumns[c]));
      }
      if (!std::isfinite(v)) {
        throw InputError("value must be finite", file, line_number, std::string(kColumns[c]));
      }
      if (c == 4 && v < 0.0) {
        throw InputError("weight must be >= 0", file, line_number, "weight");
      }
      values.push_back(c < 4 ? v * unit : v);
    }
  }
  if (columns == 0)
    throw InputError("empty file: expected a pairs CSV header", file);
  const Eigen::Index n = static_cast<Eigen::Index>(values.size() / columns);
  if (n == 0)
    throw InputError("no pairs after the header", file);
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, n);
  pairs.points_in_grid.resize(2, n);
  if (columns == 5)
    pairs.weights.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* row = values.data() + static_cast<std::size_t>(i) * columns;
    pairs.points_in_plan.col(i) << row[0], row[1];
    pairs.points_in_grid.col(i) << row[2], row[3];
    if (columns == 5)
      pairs.weights[i] = row[4];
  }
  return pairs;
}

void write_pairs_csv(const ReferencePairs& pairs, const std::filesystem::path& path, double unit) {
  std::string out = pairs.has_weights() ? "plan_x,plan_y,grid_x,grid_y,weight\n"
                                        : "plan_x,plan_y,grid_x,grid_y\n";
  out.reserve(out.size() + static_cast<std::size_t>(pairs.size()) * 80);
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    fmt::format_to(std::back_inserter(out), "{},{},{},{}", pairs.points_in_plan(0, i) / unit,
                   pairs.points_in_plan(1, i) / unit, pairs.points_in_grid(0, i) / unit,
                   pairs.points_in_grid(1, i) / unit);
    if (pairs.has_weights())
      fmt::format_to(std::back_inserter(out), ",{}", pairs.weights[i]);
    out += '\n';
  }
  write_file_atomically(path, out);
}

}  // namespace floorgrid::io
