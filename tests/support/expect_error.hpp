#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"

namespace floorgrid::test {

/// Expects `fn` to throw an InputError whose message contains every one of `parts`.
template <typename Fn>
void expect_input_error(Fn&& fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "no InputError thrown (expected one mentioning '"
                  << (parts.empty() ? std::string() : parts.front()) << "')";
  } catch (const InputError& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message '" << e.what() << "' lacks '" << part << "'";
    }
  }
}

}  // namespace floorgrid::test
