#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace floorgrid {

/// The values a number option may take: from `min` to `max`, each end included unless it is
/// open. The default is any finite number; an end at infinity that is not open admits infinity.
struct OptionRange {
  double min = -std::numeric_limits<double>::infinity();  ///< lower end
  double max = std::numeric_limits<double>::infinity();   ///< upper end
  bool min_open = true;                                   ///< `min` itself is outside
  bool max_open = true;                                   ///< `max` itself is outside

  /// Whether `value` lies in the range (NaN never does).
  constexpr bool contains(double value) const {
    return (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
  }
  /// The rule as a reader states it: "in (0, 1]", "a finite number > 0", "a whole number >= 1"
  /// (`whole`: of an integer option).
  std::string text(bool whole = false) const;
};

/// [min, +inf): at least `min`, finite.
constexpr OptionRange at_least(double min) {
  return {.min = min,
          .max = std::numeric_limits<double>::infinity(),
          .min_open = false,
          .max_open = true};
}
/// (min, +inf): more than `min`, finite.
constexpr OptionRange above(double min) {
  return {.min = min,
          .max = std::numeric_limits<double>::infinity(),
          .min_open = true,
          .max_open = true};
}
/// [min, max].
constexpr OptionRange between(double min, double max) {
  return {.min = min, .max = max, .min_open = false, .max_open = false};
}
/// (min, max].
constexpr OptionRange above_to(double min, double max) {
  return {.min = min, .max = max, .min_open = true, .max_open = false};
}
/// Any finite number.
constexpr OptionRange any_number() {
  return {};
}

/// What `config --dump` says of one option besides its value, and what a reader accepts.
struct OptionInfo {
  std::string_view unit;                  ///< "m", "rad", "scans", ... ("" when unitless)
  std::string_view doc;                   ///< one line
  std::vector<std::string_view> choices;  ///< the values a text option may take (empty: any)
  /// The values a number option may take: an options file's value outside is refused, naming
  /// the file, the line and the option (unset: any value of the option's type).
  std::optional<OptionRange> range{};
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
  /// A rule between fields of the group being visited (called after them): when `holds` is
  /// false, a visitor that reads refuses `field` saying it must be `rule` ("max must be >= min").
  /// Visitors that print ignore it.
  virtual void require(bool holds, std::string_view field, std::string_view rule) {
    (void)holds;
    (void)field;
    (void)rule;
  }
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
