#include "floorgrid/core/option_visitor.hpp"

#include <cmath>
#include <sstream>

namespace floorgrid {

namespace {

/// A bound as a reader writes it: whole numbers in full (1000000, not 1e+06), others shortest.
std::string bound_text(double value) {
  if (std::isinf(value))
    return value > 0 ? ".inf" : "-.inf";
  std::ostringstream out;
  if (value == std::floor(value) && std::abs(value) < 1e15)
    out << static_cast<long long>(value);
  else
    out << value;
  return out.str();
}

}  // namespace

std::string OptionRange::text(bool whole) const {
  const std::string kind = whole ? "a whole number " : "a finite number ";
  const bool low = !std::isinf(min) || !min_open;
  const bool high = !std::isinf(max) || !max_open;
  if (low && high) {
    return (whole ? "a whole number in " : "in ") + std::string(min_open ? "(" : "[") +
           bound_text(min) + ", " + bound_text(max) + (max_open ? ")" : "]");
  }
  if (low)
    return kind + std::string(min_open ? "> " : ">= ") + bound_text(min);
  if (high)
    return kind + std::string(max_open ? "< " : "<= ") + bound_text(max);
  return whole ? "a whole number" : "a finite number";
}

}  // namespace floorgrid
