#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace floorgrid::app {

/// A progress line on stderr, redrawn in place at most ten times a second, only when stderr is
/// a terminal (so logs and pipes stay clean).
class ProgressLine {
 public:
  ProgressLine();
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Shows `stage: done/total` with the rate per second since the stage began, and `detail`.
  void update(const std::string& stage, std::size_t done, std::size_t total,
              const std::string& detail = {});
  /// Clears the line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_ = false;
  bool shown_ = false;
  std::string stage_;
  Clock::time_point stage_start_, last_draw_;
};

}  // namespace floorgrid::app
