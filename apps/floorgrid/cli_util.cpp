#include "apps/floorgrid/cli_util.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/report/report_html.hpp"

namespace floorgrid::app {

CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t seed = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seed);
        if (error == std::errc::result_out_of_range)
          return "a seed must be at most 2^64 - 1 = 18446744073709551615 (got " + text + ")";
        if (error != std::errc() || end != text.data() + text.size())
          return "a seed must be a whole number from 0 to 2^64 - 1 (got " + text + ")";
        return {};
      },
      "SEED");
}

std::vector<double> parse_numbers(const std::string& text, const std::string& option,
                                  const std::vector<std::size_t>& counts) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? comma : comma - start);
    double v = 0.0;
    const char* begin = part.data();
    const char* end = part.data() + part.size();
    const auto [ptr, ec] = std::from_chars(begin, end, v);
    if (ec != std::errc() || ptr != end || part.empty() || !std::isfinite(v)) {
      throw InputError(fmt::format("'{}' is not a finite number (in '{}')", part, text), {}, 0,
                       option);
    }
    values.push_back(v);
    if (comma == std::string::npos)
      break;
    start = comma + 1;
  }
  if (std::find(counts.begin(), counts.end(), values.size()) == counts.end()) {
    throw InputError(fmt::format("expected {} comma-separated numbers (got {} in '{}')",
                                 fmt::join(counts, " or "), values.size(), text),
                     {}, 0, option);
  }
  return values;
}

Pose2 parse_pose(const std::string& text, const std::string& option) {
  const auto v = parse_numbers(text, option, {2, 3});
  return {v[0], v[1], v.size() == 3 ? v[2] : 0.0};
}

void refuse_overwriting_input(const std::string& input, const std::string& output,
                              const std::string& option) {
  std::error_code error;
  const auto a = std::filesystem::weakly_canonical(input, error);
  const auto b = std::filesystem::weakly_canonical(output, error);
  if (!error && a == b) {
    throw InputError(fmt::format("'{}' is also the input: it would be overwritten", output), {}, 0,
                     option);
  }
}

void write_report(const std::filesystem::path& out) {
  const auto start = std::chrono::steady_clock::now();
  try {
    const std::filesystem::path report = io::write_report_html(out);
    fmt::print("report      {} ({:.2f} s; open it in a browser, it needs no network)\n",
               report.string(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const std::exception& e) {
    spdlog::warn("report.html not written: {}", e.what());
  }
}

}  // namespace floorgrid::app
