#include "floorgrid/io/formats/scans_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/csv_lines.hpp"

namespace floorgrid::io {

namespace {

void append_filter(std::string& out, const FilterRecord& r) {
  fmt::format_to(std::back_inserter(out), ",{},{},{},{},{},", r.pose.x, r.pose.y, r.pose.theta,
                 to_string(r.state), r.converged ? 1 : 0);
  if (std::isfinite(r.fit))
    fmt::format_to(std::back_inserter(out), "{:.4f}", r.fit);
  fmt::format_to(std::back_inserter(out), ",{}", r.estimate.scale);
}

/// The scan matched pose (the one pairs are made from, before the pose pull is taken out of
/// the plan's) when the match was accepted, else empty fields.
void append_matched(std::string& out, const FilterRecord& r) {
  if (r.matched && r.match.ok()) {
    fmt::format_to(std::back_inserter(out), ",{},{},{}", r.match.pose.x, r.match.pose.y,
                   r.match.pose.theta);
  } else {
    out += ",,,";
  }
}

}  // namespace

void write_scans_csv(const DualLocalization& localization, const RobotLog& log,
                     const std::filesystem::path& path) {
  std::string out =
      "scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,plan_scale,grid_x,"
      "grid_y,grid_theta,grid_state,grid_converged,grid_fit,grid_scale,consistent,pairs,"
      "plan_matched_x,plan_matched_y,plan_matched_theta,grid_matched_x,grid_matched_y,"
      "grid_matched_theta\n";
  out.reserve(out.size() + localization.scans.size() * 240);
  for (const ScanRecord& r : localization.scans) {
    const double time = r.scan < log.scans.size() ? log.scans[r.scan].timestamp : std::nan("");
    fmt::format_to(std::back_inserter(out), "{},{}", r.scan, time);
    append_filter(out, r.plan);
    append_filter(out, r.grid);
    fmt::format_to(std::back_inserter(out), ",{},{}", r.consistent ? 1 : 0, r.pairs);
    append_matched(out, r.plan);
    append_matched(out, r.grid);
    out += '\n';
  }
  write_file_atomically(path, out);
}

std::vector<TimedPose> read_grid_track(const std::filesystem::path& path) {
  constexpr std::array<std::string_view, 5> kNeeded = {"time", "grid_x", "grid_y", "grid_theta",
                                                       "grid_state"};
  CsvLines lines(path);
  std::vector<std::string_view> fields;
  if (!lines.next(fields))
    throw InputError("empty file: expected a scans.csv header", lines.file());
  std::array<std::size_t, kNeeded.size()> column{};
  for (std::size_t k = 0; k < kNeeded.size(); ++k) {
    const auto it = std::find(fields.begin(), fields.end(), kNeeded[k]);
    if (it == fields.end()) {
      throw InputError(fmt::format("no '{}' column in the header", kNeeded[k]), lines.file(),
                       lines.line(), std::string(kNeeded[k]));
    }
    column[k] = static_cast<std::size_t>(it - fields.begin());
  }
  const std::size_t width = fields.size();
  std::vector<TimedPose> track;
  while (lines.next(fields)) {
    if (fields.size() != width) {
      throw InputError(fmt::format("expected {} fields, got {}", width, fields.size()),
                       lines.file(), lines.line());
    }
    if (fields[column[4]] != to_string(FilterState::tracking))
      continue;  // a filter still searching or lost has no pose worth showing
    TimedPose p;
    const std::string_view time = fields[column[0]];
    p.time = time == "nan" || time.empty() ? std::nan("") : lines.number(time, "time", 1e12);
    p.pose_in_grid.x = lines.number(fields[column[1]], "grid_x", kMaxCoordinate);
    p.pose_in_grid.y = lines.number(fields[column[2]], "grid_y", kMaxCoordinate);
    p.pose_in_grid.theta = lines.number(fields[column[3]], "grid_theta", 100.0);
    track.push_back(p);
  }
  return track;
}

}  // namespace floorgrid::io
