#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace floorgrid {

/// What `config --dump` says of one option besides its value.
struct OptionInfo {
  std::string_view unit;                  ///< "m", "rad", "scans", ... ("" when unitless)
  std::string_view doc;                   ///< one line
  std::vector<std::string_view> choices;  ///< the values a text option may take (empty: any)
};

/// Walks the fields of an options struct, each with its name, unit and a line of
/// documentation: the one list from which `config --dump` prints every option and its default,
/// and from which `--config FILE` reads them back (STYLE habit 3: a default lives in the struct,
/// nowhere else). A visitor may read the fields or write them.
class OptionVisitor {
 public:
  virtual ~OptionVisitor() = default;
  /// A number.
  virtual void field(std::string_view name, double& value, const OptionInfo& info) = 0;
  /// An integer.
  virtual void field(std::string_view name, int& value, const OptionInfo& info) = 0;
  /// A large integer (Eigen::Index).
  virtual void field(std::string_view name, long& value, const OptionInfo& info) = 0;
  /// A count, a size or a seed (never negative).
  virtual void field(std::string_view name, std::size_t& value, const OptionInfo& info) = 0;
  /// A switch.
  virtual void field(std::string_view name, bool& value, const OptionInfo& info) = 0;
  /// A text (with `info.choices`: one of them).
  virtual void field(std::string_view name, std::string& value, const OptionInfo& info) = 0;
  /// A number that may be left unset.
  virtual void field(std::string_view name, std::optional<double>& value,
                     const OptionInfo& info) = 0;
  /// A list of texts.
  virtual void field(std::string_view name, std::vector<std::string>& value,
                     const OptionInfo& info) = 0;
  /// A nested options struct: `members` visits its fields with this visitor.
  virtual void group(std::string_view name, std::string_view doc,
                     const std::function<void()>& members) = 0;
};

static_assert(std::is_same_v<std::uint64_t, std::size_t>,
              "seeds (std::uint64_t) are visited as counts (std::size_t)");

/// An enum option, visited as the text of its value: `names` lists every value with its text.
template <typename Enum>
void enum_field(OptionVisitor& visitor, std::string_view name, Enum& value,
                std::initializer_list<std::pair<std::string_view, Enum>> names,
                std::string_view doc) {
  OptionInfo info{.unit = "", .doc = doc, .choices = {}};
  std::string text;
  for (const auto& [label, option] : names) {
    info.choices.push_back(label);
    if (option == value)
      text = std::string(label);
  }
  visitor.field(name, text, info);
  // A visitor that writes checks the text against the choices (naming where it came from).
  for (const auto& [label, option] : names) {
    if (label == text)
      value = option;
  }
}

}  // namespace floorgrid
