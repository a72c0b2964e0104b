#pragma once

#include <cstdint>
#include <random>

namespace floorgrid {

/// The project's random source: a 64-bit Mersenne Twister with its own uniform and normal
/// transforms (the standard library's distributions are implementation-defined), so a seed
/// gives the same numbers on every platform and compiler.
class Random {
 public:
  /// A source seeded with `seed`.
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive); hi >= lo.
  std::int64_t integer(std::int64_t lo, std::int64_t hi);
  /// Normal with mean 0 and standard deviation `sigma` (Marsaglia's polar method).
  double normal(double sigma = 1.0);
  /// True with probability p.
  bool bernoulli(double p) { return uniform() < p; }
  /// A seed for an independent child source (so that adding draws in one part of a pipeline
  /// does not shift the numbers of another).
  std::uint64_t fork() { return engine_(); }
  /// The raw 64-bit engine, for algorithms that need one.
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace floorgrid
