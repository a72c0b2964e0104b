#include "floorgrid/io/scans_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <string>

#include "floorgrid/io/atomic_file.hpp"

namespace floorgrid::io {

namespace {

void append_filter(std::string& out, const FilterRecord& r) {
  fmt::format_to(std::back_inserter(out), ",{},{},{},{},{},", r.pose.x, r.pose.y, r.pose.theta,
                 to_string(r.state), r.converged ? 1 : 0);
  if (std::isfinite(r.fit))
    fmt::format_to(std::back_inserter(out), "{:.4f}", r.fit);
  fmt::format_to(std::back_inserter(out), ",{}", r.estimate.scale);
}

}  // namespace

void write_scans_csv(const DualLocalization& localization, const RobotLog& log,
                     const std::filesystem::path& path) {
  std::string out =
      "scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,plan_scale,grid_x,"
      "grid_y,grid_theta,grid_state,grid_converged,grid_fit,grid_scale,consistent,pairs\n";
  out.reserve(out.size() + localization.scans.size() * 160);
  for (const ScanRecord& r : localization.scans) {
    const double time = r.scan < log.scans.size() ? log.scans[r.scan].timestamp : std::nan("");
    fmt::format_to(std::back_inserter(out), "{},{}", r.scan, time);
    append_filter(out, r.plan);
    append_filter(out, r.grid);
    fmt::format_to(std::back_inserter(out), ",{},{}\n", r.consistent ? 1 : 0, r.pairs);
  }
  write_file_atomically(path, out);
}

}  // namespace floorgrid::io
