#pragma once

#include <cstddef>
#include <utility>

namespace floorgrid::test {

namespace detail {
/// Converts to any field type, in unevaluated contexts only.
struct AnyField {
  std::size_t index;
  template <typename T>
  operator T&() const noexcept;
  template <typename T>
  operator T&&() const noexcept;
};

template <typename T, std::size_t... I>
constexpr bool brace_constructible(std::index_sequence<I...>) {
  return requires {
    T{AnyField{I}...};
  };
}
}  // namespace detail

/// The number of fields of an aggregate (an options struct): the most initializers it takes.
/// Lets a test check that a list of fields (an option visitor) names every one of them.
template <typename T, std::size_t N = 0>
constexpr std::size_t field_count() {
  if constexpr (N > 128)
    return N;
  else if constexpr (detail::brace_constructible<T>(std::make_index_sequence<N + 1>{}))
    return field_count<T, N + 1>();
  else
    return N;
}

}  // namespace floorgrid::test
