#pragma once

namespace floorgrid::io {

/// This machine's physical memory in GiB (16 when it cannot be read).
double physical_memory_gb();

/// The default limit of what one job may allocate: half of the physical memory, GiB.
double default_memory_limit_gb();

}  // namespace floorgrid::io
