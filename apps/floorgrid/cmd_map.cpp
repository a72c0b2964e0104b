// `floorgrid map --model FILE [--inverse] x,y[,theta] ...` or `--points IN.csv --out OUT.csv`.
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/points_csv.hpp"

namespace floorgrid::app {

void add_map_command(CLI::App& root) {
  auto* cmd =
      root.add_subcommand("map", "Map points or poses through a model, plan to grid or back");
  struct Args {
    std::string model, points, out;
    bool inverse = false;
    std::optional<double> max_error;
    std::vector<std::string> values;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--model", args->model, "model file written by `fit` or `align`")->required();
  cmd->add_flag("--inverse", args->inverse, "map grid to plan instead of plan to grid");
  cmd->add_option("--points", args->points, "CSV of points: header x,y or x,y,theta");
  cmd->add_option("--out", args->out, "CSV to write with --points");
  cmd->add_option("--max-error", args->max_error,
                  fmt::format("metres: a point whose 95% error bound (2 std_m) exceeds this is "
                              "flagged uncertain, not ok (default: the model file's, else {:g})",
                              MappingCommonOptions{}.max_error));
  cmd->add_option("POINTS", args->values, "points x,y or poses x,y,theta (radians)");
  cmd->callback([args] {
    if (args->points.empty() == args->values.empty()) {
      throw InputError("give either points on the command line or --points IN.csv --out OUT.csv",
                       {}, 0, "--points");
    }
    if (!args->points.empty() && args->out.empty()) {
      throw InputError("--points needs --out OUT.csv", {}, 0, "--out");
    }
    const auto model = io::read_model(args->model);
    if (args->max_error) {
      if (!(*args->max_error > 0.0 && *args->max_error <= kMaxCoordinate)) {
        throw InputError(
            fmt::format("must be a distance in (0, 1e7] metres (got {})", *args->max_error), {}, 0,
            "--max-error");
      }
      model->set_max_error(*args->max_error);
    }
    // Coordinates beyond kMaxCoordinate metres are not physical (their squared distances
    // overflow): refused, in the model's units.
    const double max_abs = kMaxCoordinate / model->unit();
    if (!args->points.empty()) {
      refuse_overwriting_input(args->points, args->out, "--out");
      const io::PointsTable table = io::read_points_csv(args->points, max_abs);
      // Rows are independent and models are immutable once loaded: two threads share them.
      std::vector<io::MappedRow> rows(static_cast<std::size_t>(table.points.cols()));
      parallel_chunks(rows.size(), 4096, kDefaultThreads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
          const auto i = static_cast<Eigen::Index>(r);
          const double* heading = table.has_headings() ? &table.headings[i] : nullptr;
          rows[r] = io::map_row(*model, table.points.col(i), heading, args->inverse);
        }
      });
      io::write_mapped_csv(rows, table.has_headings(), args->out);
      fmt::print("mapped {} {} with {} ({}) to {}\n", rows.size(),
                 table.has_headings() ? "poses" : "points", model->name(),
                 args->inverse ? "grid -> plan" : "plan -> grid", args->out);
      return;
    }
    for (const std::string& text : args->values) {
      const auto v = parse_numbers(text, "POINTS", {2, 3});
      if (std::abs(v[0]) > max_abs || std::abs(v[1]) > max_abs) {
        throw InputError(
            fmt::format("'{}' lies beyond {:g}: not a physical coordinate", text, max_abs), {}, 0,
            "POINTS");
      }
      const double* heading = v.size() == 3 ? &v[2] : nullptr;
      const io::MappedRow row = io::map_row(*model, {v[0], v[1]}, heading, args->inverse);
      if (row.mapped.flag == MapFlag::not_invertible) {
        fmt::print("{} -> not_invertible\n", text);
        continue;
      }
      std::string result = fmt::format("{:.6f},{:.6f}", row.mapped.point.x(), row.mapped.point.y());
      if (row.heading)
        result += fmt::format(",{:.6f}", *row.heading);
      std::string std_text = row.mapped.std_m ? fmt::format("{:.4f} m", *row.mapped.std_m) : "n/a";
      fmt::print("{} -> {}  std {}  nearest pair {:.3f} m  {}\n", text, result, std_text,
                 row.mapped.nearest_pair_m, to_string(row.mapped.flag));
    }
  });
}

}  // namespace floorgrid::app
