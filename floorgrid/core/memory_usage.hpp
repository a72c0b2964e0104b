#pragma once

namespace floorgrid {

/// The process's peak resident memory so far, in MiB (getrusage's ru_maxrss): it only grows, so
/// read at the end of each stage of a job it tells which stage raised the peak. 0 where the
/// system does not say.
double peak_resident_mib();

}  // namespace floorgrid
