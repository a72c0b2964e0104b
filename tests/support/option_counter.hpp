#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/core/option_visitor.hpp"

namespace floorgrid::test {

/// Counts the fields and groups a visit names at its top level (with field_count, a test that
/// every field of an options struct is visited).
class TopLevelCounter final : public OptionVisitor {
 public:
  std::size_t count = 0;  ///< top-level fields and groups seen
  void field(std::string_view, double&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, int&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, long&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, std::size_t&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, bool&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, std::string&, const OptionInfo&) override { count += depth_ == 0; }
  void field(std::string_view, std::optional<double>&, const OptionInfo&) override {
    count += depth_ == 0;
  }
  void field(std::string_view, std::vector<std::string>&, const OptionInfo&) override {
    count += depth_ == 0;
  }
  void group(std::string_view, std::string_view, const std::function<void()>& members) override {
    count += depth_ == 0;
    ++depth_;
    members();
    --depth_;
  }

 private:
  int depth_ = 0;
};

}  // namespace floorgrid::test
