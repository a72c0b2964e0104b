#include "floorgrid/geometry/big_integer.hpp"

#include <bit>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace floorgrid::detail {

BigInteger BigInteger::from_double(double x, int unit_exponent) {
  BigInteger result;
  if (x == 0.0)
    return result;
  assert(std::isfinite(x));
  // x = mantissa * 2^exponent with an integer mantissa of 53 bits.
  int exponent = 0;
  const double fraction = std::frexp(std::fabs(x), &exponent);
  const auto mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 53));
  const int shift = exponent - 53 - unit_exponent;
  // Drop the low zero bits that lie below the unit (a subnormal x has a short mantissa).
  std::uint64_t m = mantissa;
  int s = shift;
  if (s < 0) {
    assert(std::countr_zero(m) >= -s);
    m >>= -s;
    s = 0;
  }
  const int limb_shift = s / 32;
  const int bit_shift = s % 32;
  result.magnitude_.assign(static_cast<std::size_t>(limb_shift), 0u);
  // m << bit_shift spans at most 53 + 31 bits: three limbs.
  const std::uint64_t low = m << bit_shift;
  const std::uint64_t high = bit_shift == 0 ? 0 : (m >> (64 - bit_shift));
  result.magnitude_.push_back(static_cast<std::uint32_t>(low));
  result.magnitude_.push_back(static_cast<std::uint32_t>(low >> 32));
  result.magnitude_.push_back(static_cast<std::uint32_t>(high));
  result.negative_ = x < 0.0;
  result.trim();
  return result;
}

double BigInteger::approximate(int& exponent) const {
  exponent = 0;
  if (magnitude_.empty())
    return 0.0;
  // The top three limbs carry more than the 53 bits a double holds.
  const std::size_t n = magnitude_.size();
  double m = 0.0;
  const std::size_t first = n >= 3 ? n - 3 : 0;
  for (std::size_t i = n; i-- > first;)
    m = m * 4294967296.0 + static_cast<double>(magnitude_[i]);
  exponent = static_cast<int>(32 * first);
  return negative_ ? -m : m;
}

int BigInteger::compare_magnitudes(const std::vector<std::uint32_t>& a,
                                   const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size())
    return a.size() < b.size() ? -1 : 1;
  for (std::size_t i = a.size(); i-- > 0;) {
    if (a[i] != b[i])
      return a[i] < b[i] ? -1 : 1;
  }
  return 0;
}

std::vector<std::uint32_t> BigInteger::add_magnitudes(const std::vector<std::uint32_t>& a,
                                                      const std::vector<std::uint32_t>& b) {
  const std::vector<std::uint32_t>& longer = a.size() >= b.size() ? a : b;
  const std::vector<std::uint32_t>& shorter = a.size() >= b.size() ? b : a;
  std::vector<std::uint32_t> sum(longer.size() + 1, 0u);
  std::uint64_t carry = 0;
  for (std::size_t i = 0; i < longer.size(); ++i) {
    const std::uint64_t s = carry + longer[i] + (i < shorter.size() ? shorter[i] : 0u);
    sum[i] = static_cast<std::uint32_t>(s);
    carry = s >> 32;
  }
  sum[longer.size()] = static_cast<std::uint32_t>(carry);
  return sum;
}

std::vector<std::uint32_t> BigInteger::subtract_magnitudes(const std::vector<std::uint32_t>& a,
                                                           const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> difference(a.size(), 0u);
  std::int64_t borrow = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::int64_t d = static_cast<std::int64_t>(a[i]) - borrow -
                     static_cast<std::int64_t>(i < b.size() ? b[i] : 0u);
    borrow = 0;
    if (d < 0) {
      d += std::int64_t{1} << 32;
      borrow = 1;
    }
    difference[i] = static_cast<std::uint32_t>(d);
  }
  assert(borrow == 0);
  return difference;
}

BigInteger BigInteger::signed_sum(const BigInteger& a, bool b_negative,
                                  const std::vector<std::uint32_t>& b_magnitude) {
  BigInteger result;
  if (a.negative_ == b_negative) {
    result.magnitude_ = add_magnitudes(a.magnitude_, b_magnitude);
    result.negative_ = a.negative_;
  } else if (compare_magnitudes(a.magnitude_, b_magnitude) >= 0) {
    result.magnitude_ = subtract_magnitudes(a.magnitude_, b_magnitude);
    result.negative_ = a.negative_;
  } else {
    result.magnitude_ = subtract_magnitudes(b_magnitude, a.magnitude_);
    result.negative_ = b_negative;
  }
  result.trim();
  return result;
}

BigInteger operator+(const BigInteger& a, const BigInteger& b) {
  return BigInteger::signed_sum(a, b.negative_, b.magnitude_);
}

BigInteger operator-(const BigInteger& a, const BigInteger& b) {
  return BigInteger::signed_sum(a, !b.negative_, b.magnitude_);
}

BigInteger operator*(const BigInteger& a, const BigInteger& b) {
  BigInteger result;
  if (a.magnitude_.empty() || b.magnitude_.empty())
    return result;
  result.magnitude_.assign(a.magnitude_.size() + b.magnitude_.size(), 0u);
  for (std::size_t i = 0; i < a.magnitude_.size(); ++i) {
    std::uint64_t carry = 0;
    for (std::size_t j = 0; j < b.magnitude_.size(); ++j) {
      const std::uint64_t t = static_cast<std::uint64_t>(a.magnitude_[i]) * b.magnitude_[j] +
                              result.magnitude_[i + j] + carry;
      result.magnitude_[i + j] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    result.magnitude_[i + b.magnitude_.size()] = static_cast<std::uint32_t>(carry);
  }
  result.negative_ = a.negative_ != b.negative_;
  result.trim();
  return result;
}

void BigInteger::trim() {
  while (!magnitude_.empty() && magnitude_.back() == 0u)
    magnitude_.pop_back();
  if (magnitude_.empty())
    negative_ = false;
}

}  // namespace floorgrid::detail
