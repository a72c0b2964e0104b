#pragma once

#include <sstream>
#include <string>
#include <string_view>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

/// "(got <value>)", for messages about a value out of range.
template <typename T>
std::string got(const T& value) {
  std::ostringstream out;
  out << "(got " << value << ")";
  return out.str();
}

/// Validates one option at the boundary (STYLE habit 4): when `valid` is false, throws
/// InputError naming `field` (e.g. "ransac.inlier_threshold") with "must be <rule> (got <value>)".
template <typename T>
void require_option(bool valid, std::string_view field, const T& value, std::string_view rule) {
  if (valid)
    return;
  std::ostringstream message;
  message << "must be " << rule << ' ' << got(value);
  throw InputError(message.str(), {}, 0, std::string(field));
}

/// require_option for a field of an options struct: names it "<prefix>.<field>".
template <typename T>
void require_option(bool valid, std::string_view prefix, std::string_view field, const T& value,
                    std::string_view rule) {
  if (valid)
    return;
  std::string name(prefix);
  name += '.';
  name += field;
  require_option(false, name, value, rule);
}

}  // namespace floorgrid
