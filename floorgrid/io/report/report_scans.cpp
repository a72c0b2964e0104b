#include "floorgrid/io/report/report_scans.hpp"

#include <algorithm>
#include <charconv>
#include <string>
#include <vector>

namespace floorgrid::io {

namespace {

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos)
      return fields;
    start = comma + 1;
  }
}

long long integer(std::string_view field) {
  long long v = 0;
  std::from_chars(field.data(), field.data() + field.size(), v);
  return v;
}

struct Row {
  long long scan;
  bool plan, grid;
  long long pairs;
};

}  // namespace

ScanTrack scan_track(std::string_view text, int max_points) {
  ScanTrack track;
  std::vector<Row> rows;
  int scan_col = -1, plan_col = -1, grid_col = -1, pairs_col = -1;
  bool header = true;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    if (!line.empty() && line.back() == '\r')
      line.remove_suffix(1);
    if (line.empty())
      continue;
    const std::vector<std::string_view> fields = split_fields(line);
    if (header) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const int c = static_cast<int>(i);
        if (fields[i] == "scan")
          scan_col = c;
        else if (fields[i] == "plan_converged")
          plan_col = c;
        else if (fields[i] == "grid_converged")
          grid_col = c;
        else if (fields[i] == "pairs")
          pairs_col = c;
      }
      if (scan_col < 0 || plan_col < 0 || grid_col < 0 || pairs_col < 0)
        return track;
      header = false;
      continue;
    }
    const auto last = static_cast<std::size_t>(std::max({scan_col, plan_col, grid_col, pairs_col}));
    if (fields.size() <= last)
      continue;
    rows.push_back({integer(fields[scan_col]), integer(fields[plan_col]) != 0,
                    integer(fields[grid_col]) != 0, integer(fields[pairs_col])});
  }
  if (rows.empty())
    return track;
  track.scans = static_cast<int>(rows.size());
  track.bucket = (track.scans + max_points - 1) / max_points;
  nlohmann::json scan = nlohmann::json::array(), grid = nlohmann::json::array(),
                 plan = nlohmann::json::array(), paired = nlohmann::json::array(),
                 pairs = nlohmann::json::array();
  for (std::size_t first = 0; first < rows.size(); first += track.bucket) {
    const std::size_t last = std::min(rows.size(), first + track.bucket);
    int plan_count = 0, grid_count = 0, paired_count = 0;
    long long pair_sum = 0;
    for (std::size_t i = first; i < last; ++i) {
      plan_count += rows[i].plan;
      grid_count += rows[i].grid;
      paired_count += rows[i].pairs > 0;
      pair_sum += rows[i].pairs;
    }
    track.plan_converged += plan_count;
    track.grid_converged += grid_count;
    track.with_pairs += paired_count;
    // A chart point stands for its bucket: "yes" when at least half of its scans were.
    const auto half = [&](int count) { return 2 * count >= static_cast<int>(last - first); };
    scan.push_back(rows[first].scan);
    grid.push_back(half(grid_count) ? nlohmann::json(1) : nlohmann::json(nullptr));
    plan.push_back(half(plan_count) ? nlohmann::json(1) : nlohmann::json(nullptr));
    paired.push_back(half(paired_count) ? nlohmann::json(1) : nlohmann::json(nullptr));
    pairs.push_back(pair_sum);
  }
  track.chart = {{"scan", scan},     {"grid", grid},   {"plan", plan},
                 {"paired", paired}, {"pairs", pairs}, {"bucket", track.bucket}};
  return track;
}

}  // namespace floorgrid::io
