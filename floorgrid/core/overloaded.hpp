#pragma once

namespace floorgrid {

/// A visitor made of lambdas, one per alternative: `std::visit(Overloaded{[](int) {}, ...}, v)`.
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace floorgrid
