#include "floorgrid/io/files/system_memory.hpp"

#include <unistd.h>

namespace floorgrid::io {

double physical_memory_gb() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0)
    return 16.0;
  return static_cast<double>(pages) * static_cast<double>(page) / (1u << 30);
}

double default_memory_limit_gb() {
  return 0.5 * physical_memory_gb();
}

}  // namespace floorgrid::io
