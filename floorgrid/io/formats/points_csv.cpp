#include "floorgrid/io/formats/points_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/csv_lines.hpp"

namespace floorgrid::io {

PointsTable read_points_csv(const std::filesystem::path& path, double max_abs) {
  const std::string file = path.string();
  static const char* kNames[] = {"x", "y", "theta"};
  CsvLines lines(path);
  std::vector<std::string_view> fields;
  std::size_t columns = 0;
  std::vector<double> values;
  while (lines.next(fields)) {
    if (columns == 0) {
      if ((fields.size() != 2 && fields.size() != 3) || fields[0] != "x" || fields[1] != "y" ||
          (fields.size() == 3 && fields[2] != "theta")) {
        throw InputError("header must be x,y or x,y,theta", file, lines.line());
      }
      columns = fields.size();
      continue;
    }
    if (fields.size() != columns) {
      throw InputError(fmt::format("expected {} values, got {}", columns, fields.size()), file,
                       lines.line());
    }
    for (std::size_t c = 0; c < columns; ++c)
      values.push_back(lines.number(fields[c], kNames[c], c < 2 ? max_abs : 1e300));
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

MappedRow map_row(const PointMapping& model, const Eigen::Vector2d& point, const double* heading,
                  bool inverse) {
  const double unit = model.unit();
  const Eigen::Vector2d p = point * unit;
  MappedRow row;
  row.mapped = inverse ? model.map_inverse(p) : model.map_forward(p);
  if (row.mapped.flag != MapFlag::not_invertible) {
    // The heading through the Jacobian at the plan point (the inverse's is solved once).
    if (heading) {
      row.heading = inverse ? model.heading_in_plan(row.mapped.point, *heading)
                            : model.heading_in_grid(p, *heading);
    }
    row.mapped.point /= unit;
  }
  return row;
}

}  // namespace floorgrid::io
