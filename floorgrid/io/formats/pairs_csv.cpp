#include "floorgrid/io/formats/pairs_csv.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/csv_lines.hpp"

namespace floorgrid::io {

namespace {

constexpr std::array<std::string_view, 5> kColumns = {"plan_x", "plan_y", "grid_x", "grid_y",
                                                      "weight"};

}  // namespace

ReferencePairs read_pairs_csv(const std::filesystem::path& path, double unit,
                              std::vector<long>* pair_lines) {
  const std::string file = path.string();
  if (!(unit > 0.0) || !std::isfinite(unit)) {
    throw InputError(fmt::format("must be a positive number of metres per unit (got {:g})", unit),
                     file, 0, "unit");
  }
  CsvLines lines(path);
  std::vector<std::string_view> fields;
  std::vector<double> values;
  std::size_t columns = 0;
  while (lines.next(fields)) {
    if (columns == 0) {
      if (fields.size() < 4 || fields.size() > 5) {
        throw InputError("header must be plan_x,plan_y,grid_x,grid_y[,weight]", file, lines.line());
      }
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c] != kColumns[c]) {
          throw InputError(fmt::format("header column {} must be '{}' (got '{}'); expected "
                                       "plan_x,plan_y,grid_x,grid_y[,weight]",
                                       c + 1, kColumns[c], fields[c]),
                           file, lines.line());
        }
      }
      columns = fields.size();
      continue;
    }
    if (fields.size() != columns) {
      throw InputError(fmt::format("expected {} values, got {}", columns, fields.size()), file,
                       lines.line());
    }
    if (pair_lines != nullptr)
      pair_lines->push_back(lines.line());
    for (std::size_t c = 0; c < columns; ++c) {
      const std::string column(kColumns[c]);
      if (c < 4) {
        // Coordinates in metres must be physical (kMaxCoordinate): far beyond, squared
        // distances overflow and every model's figures turn to infinity.
        values.push_back(lines.number(fields[c], column, kMaxCoordinate / unit) * unit);
        continue;
      }
      const double weight = lines.number(fields[c], column, 1e300);
      if (weight < 0.0)
        throw InputError("weight must be >= 0", file, lines.line(), "weight");
      values.push_back(weight);
    }
  }
  if (columns == 0)
    throw InputError("empty file: expected a pairs CSV header", file);
  const Eigen::Index n = static_cast<Eigen::Index>(values.size() / columns);
  if (n == 0)
    throw InputError("no pairs after the header", file);
  if (columns == 5) {
    double total = 0.0;
    for (std::size_t i = 4; i < values.size(); i += 5)
      total += values[i];
    if (!(total > 0.0))
      throw InputError("every weight is 0: no pair would count", file, 0, "weight");
  }
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
