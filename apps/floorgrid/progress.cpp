#include "apps/floorgrid/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace floorgrid::app {

ProgressLine::ProgressLine() : enabled_(isatty(fileno(stderr)) != 0) {}

ProgressLine::~ProgressLine() {
  finish();
}

void ProgressLine::update(const std::string& stage, std::size_t done, std::size_t total,
                          const std::string& detail) {
  if (!enabled_)
    return;
  const auto now = Clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
  } else if (now - last_draw_ < std::chrono::milliseconds(100) && done < total) {
    return;
  }
  last_draw_ = now;
  const double seconds = std::chrono::duration<double>(now - stage_start_).count();
  const std::string rate = seconds > 0.2 ? fmt::format(" {:.0f}/s", done / seconds) : "";
  const std::string line =
      fmt::format("{}: {}/{}{}{}{}", stage, done, total, rate, detail.empty() ? "" : "  ", detail);
  fmt::print(stderr, "\r\033[K{}", line);
  std::fflush(stderr);
  shown_ = true;
}

void ProgressLine::finish() {
  if (enabled_ && shown_) {
    fmt::print(stderr, "\r\033[K");
    std::fflush(stderr);
  }
  shown_ = false;
  stage_.clear();
}

}  // namespace floorgrid::app
