#include "floorgrid/pipeline/memory_estimate.hpp"

namespace floorgrid {

namespace {
// Global localization's particles and hypotheses, the models' fits and the program itself.
constexpr std::size_t kFixedBytes = std::size_t{200} << 20;
// A reading is kept as a float in the log and again in each filter's prepared scans.
constexpr std::size_t kBytesPerReading = 16;
}  // namespace

std::size_t alignment_memory_bytes(std::size_t plan_cells, std::size_t gridmap_cells,
                                   std::size_t log_readings) {
  return kFixedBytes + kAlignmentBytesPerCell * (plan_cells + gridmap_cells) +
         kBytesPerReading * log_readings;
}

}  // namespace floorgrid
