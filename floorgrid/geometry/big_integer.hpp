#pragma once

#include <cstdint>
#include <vector>

namespace floorgrid::detail {

/// A signed integer of any size: the last resort of the exact predicates, for inputs whose
/// coordinates span so many binary orders of magnitude (beyond about 2^200) that the products of
/// floating-point expansions would underflow. Every finite double is an integer multiple of
/// 2^-1074, so a fixed power of two turns any set of doubles into integers of at most 2100 bits.
/// Only what the predicates need: construction from a double, +, -, *, sign and an approximation.
class BigInteger {
 public:
  /// Zero.
  BigInteger() = default;

  /// The integer x * 2^-unit_exponent. Precondition: x is finite and an integer multiple of
  /// 2^unit_exponent (true for every double when unit_exponent <= -1074).
  static BigInteger from_double(double x, int unit_exponent);

  /// -1, 0 or +1.
  int sign() const { return magnitude_.empty() ? 0 : (negative_ ? -1 : 1); }

  /// The value as m * 2^e with a double m (rounded) and an int e, so that huge values do not
  /// overflow: returns m and stores e in `exponent`. Zero gives m = 0.
  double approximate(int& exponent) const;

  /// Sum.
  friend BigInteger operator+(const BigInteger& a, const BigInteger& b);
  /// Difference.
  friend BigInteger operator-(const BigInteger& a, const BigInteger& b);
  /// Product.
  friend BigInteger operator*(const BigInteger& a, const BigInteger& b);

 private:
  static int compare_magnitudes(const std::vector<std::uint32_t>& a,
                                const std::vector<std::uint32_t>& b);
  static std::vector<std::uint32_t> add_magnitudes(const std::vector<std::uint32_t>& a,
                                                   const std::vector<std::uint32_t>& b);
  /// a - b for |a| >= |b|.
  static std::vector<std::uint32_t> subtract_magnitudes(const std::vector<std::uint32_t>& a,
                                                        const std::vector<std::uint32_t>& b);
  static BigInteger signed_sum(const BigInteger& a, bool b_negative,
                               const std::vector<std::uint32_t>& b_magnitude);
  void trim();

  bool negative_ = false;
  std::vector<std::uint32_t> magnitude_;  ///< base 2^32, least significant limb first, no leading 0
};

}  // namespace floorgrid::detail
