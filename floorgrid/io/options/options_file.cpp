#include "floorgrid/io/options/options_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/yaml_document.hpp"

namespace floorgrid::io {

namespace {

// ---- printing ----

/// A number as YAML reads it back exactly (the shortest text that round-trips).
std::string yaml_number(double value) {
  if (std::isnan(value))
    return ".nan";
  if (std::isinf(value))
    return value > 0 ? ".inf" : "-.inf";
  return fmt::format("{}", value);
}

/// A text as a double-quoted YAML scalar.
std::string yaml_text(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\')
      out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string comment(const OptionInfo& info, bool whole) {
  std::string text;
  if (!info.unit.empty())
    text += fmt::format("[{}] ", info.unit);
  text += info.doc;
  if (!info.choices.empty())
    text += fmt::format(" (one of: {})", fmt::join(info.choices, ", "));
  if (info.range)
    text += fmt::format(" ({})", info.range->text(whole));
  return text;
}

class YamlPrinter final : public OptionVisitor {
 public:
  std::string text;

  void field(std::string_view name, double& value, const OptionInfo& info) override {
    line(name, yaml_number(value), info);
  }
  void field(std::string_view name, int& value, const OptionInfo& info) override {
    line(name, std::to_string(value), info, true);
  }
  void field(std::string_view name, long& value, const OptionInfo& info) override {
    line(name, std::to_string(value), info, true);
  }
  void field(std::string_view name, std::size_t& value, const OptionInfo& info) override {
    line(name, std::to_string(value), info, true);
  }
  void field(std::string_view name, bool& value, const OptionInfo& info) override {
    line(name, value ? "true" : "false", info);
  }
  void field(std::string_view name, std::string& value, const OptionInfo& info) override {
    line(name, yaml_text(value), info);
  }
  void field(std::string_view name, std::optional<double>& value, const OptionInfo& info) override {
    line(name, value ? yaml_number(*value) : "null", info);
  }
  void field(std::string_view name, std::vector<std::string>& value,
             const OptionInfo& info) override {
    std::vector<std::string> quoted;
    for (const std::string& v : value)
      quoted.push_back(yaml_text(v));
    line(name, fmt::format("[{}]", fmt::join(quoted, ", ")), info);
  }
  void group(std::string_view name, std::string_view doc,
             const std::function<void()>& members) override {
    if (!doc.empty())
      text += fmt::format("{:{}}# {}\n", "", indent_, doc);
    text += fmt::format("{:{}}{}:\n", "", indent_, name);
    indent_ += 2;
    members();
    indent_ -= 2;
  }

 private:
  void line(std::string_view name, const std::string& value, const OptionInfo& info,
            bool whole = false) {
    const std::string note = comment(info, whole);
    text += fmt::format("{:{}}{}: {}", "", indent_, name, value);
    text += note.empty() ? "\n" : "  # " + note + "\n";
  }
  int indent_ = 0;
};

class JsonPrinter final : public OptionVisitor {
 public:
  nlohmann::ordered_json root = nlohmann::ordered_json::object();

  void field(std::string_view name, double& value, const OptionInfo& info) override {
    // JSON has no infinity or NaN: they are written as text.
    leaf(name,
         std::isfinite(value) ? nlohmann::ordered_json(value)
                              : nlohmann::ordered_json(yaml_number(value)),
         info);
  }
  void field(std::string_view name, int& value, const OptionInfo& info) override {
    leaf(name, value, info, true);
  }
  void field(std::string_view name, long& value, const OptionInfo& info) override {
    leaf(name, value, info, true);
  }
  void field(std::string_view name, std::size_t& value, const OptionInfo& info) override {
    leaf(name, value, info, true);
  }
  void field(std::string_view name, bool& value, const OptionInfo& info) override {
    leaf(name, value, info);
  }
  void field(std::string_view name, std::string& value, const OptionInfo& info) override {
    leaf(name, value, info);
  }
  void field(std::string_view name, std::optional<double>& value, const OptionInfo& info) override {
    leaf(name, value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr), info);
  }
  void field(std::string_view name, std::vector<std::string>& value,
             const OptionInfo& info) override {
    leaf(name, value, info);
  }
  void group(std::string_view name, std::string_view doc,
             const std::function<void()>& members) override {
    nlohmann::ordered_json& parent = *current_;
    nlohmann::ordered_json& child = parent[std::string(name)] = nlohmann::ordered_json::object();
    if (!doc.empty())
      child["description"] = doc;
    current_ = &child;
    members();
    current_ = &parent;
  }

 private:
  void leaf(std::string_view name, nlohmann::ordered_json value, const OptionInfo& info,
            bool whole = false) {
    nlohmann::ordered_json entry = {
        {"default", std::move(value)}, {"unit", info.unit}, {"description", info.doc}};
    if (!info.choices.empty())
      entry["choices"] = info.choices;
    if (info.range)
      entry["range"] = info.range->text(whole);
    (*current_)[std::string(name)] = std::move(entry);
  }
  nlohmann::ordered_json* current_ = &root;
};

// ---- reading ----

class YamlReader final : public OptionVisitor {
 public:
  YamlReader(const YAML::Node& root, std::string file) : file_(std::move(file)) {
    levels_.push_back({root, ""});
  }

  void field(std::string_view name, double& value, const OptionInfo& info) override {
    if (const auto node = scalar(name, "a number"))
      value = in_range(number(*node, name), *node, name, info, false);
  }
  void field(std::string_view name, int& value, const OptionInfo& info) override {
    if (const auto node = scalar(name, "an integer")) {
      const long long v = integer(*node, name);
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        fail(*node, name, "is out of range for an integer (got " + node->Scalar() + ")");
      in_range(static_cast<double>(v), *node, name, info, true);
      value = static_cast<int>(v);
    }
  }
  void field(std::string_view name, long& value, const OptionInfo& info) override {
    if (const auto node = scalar(name, "an integer")) {
      const long long v = integer(*node, name);
      in_range(static_cast<double>(v), *node, name, info, true);
      value = static_cast<long>(v);
    }
  }
  void field(std::string_view name, std::size_t& value, const OptionInfo& info) override {
    if (const auto node = scalar(name, "a whole number >= 0")) {
      const std::string& text = node->Scalar();
      std::size_t v = 0;
      const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec == std::errc::result_out_of_range)
        fail(*node, name, "must be a whole number below 2^64 (got " + text + ")");
      if (ec != std::errc() || ptr != text.data() + text.size())
        fail(*node, name, "must be a whole number >= 0 (got " + text + ")");
      in_range(static_cast<double>(v), *node, name, info, true);
      value = v;
    }
  }
  void field(std::string_view name, bool& value, const OptionInfo&) override {
    if (const auto node = scalar(name, "true or false")) {
      const std::string& text = node->Scalar();
      if (text == "true" || text == "1")
        value = true;
      else if (text == "false" || text == "0")
        value = false;
      else
        fail(*node, name, "must be true or false (got " + text + ")");
    }
  }
  void field(std::string_view name, std::string& value, const OptionInfo& info) override {
    if (const auto node = scalar(name, "a text")) {
      const std::string& text = node->Scalar();
      if (!info.choices.empty() &&
          std::find(info.choices.begin(), info.choices.end(), text) == info.choices.end()) {
        fail(*node, name,
             fmt::format("must be one of {} (got '{}')", fmt::join(info.choices, ", "), text));
      }
      value = text;
    }
  }
  void field(std::string_view name, std::optional<double>& value, const OptionInfo& info) override {
    const YAML::Node node = take(name);
    if (!node.IsDefined())
      return;
    if (node.IsNull()) {
      value.reset();
      return;
    }
    if (!node.IsScalar())
      fail(node, name, "must be a number or null");
    value = in_range(number(node, name), node, name, info, false);
  }
  void field(std::string_view name, std::vector<std::string>& value, const OptionInfo&) override {
    const YAML::Node node = take(name);
    if (!node.IsDefined())
      return;
    std::vector<std::string> texts;
    if (node.IsScalar()) {
      texts.push_back(node.Scalar());
    } else if (node.IsSequence()) {
      for (const YAML::Node& item : node) {
        if (!item.IsScalar())
          fail(item, name, "must be a list of texts");
        texts.push_back(item.Scalar());
      }
    } else if (!node.IsNull()) {
      fail(node, name, "must be a list of texts");
    }
    value = std::move(texts);
  }
  void group(std::string_view name, std::string_view,
             const std::function<void()>& members) override {
    const YAML::Node node = take(name);
    if (!node.IsDefined() || node.IsNull())
      return;
    if (!node.IsMap())
      fail(node, name, "must be a mapping of options");
    levels_.push_back({node, path(name)});
    members();
    reject_unknown();
    levels_.pop_back();
  }

  void require(bool holds, std::string_view field, std::string_view rule) override {
    if (holds)
      return;
    // At the field's line when the file gives it, else at its group's.
    const Level& level = levels_.back();
    const YAML::Node node = level.node[std::string(field)];
    fail(node.IsDefined() ? node : level.node, field, "must be " + std::string(rule));
  }

  /// Throws for the first key of the current level that no field or group took.
  void reject_unknown() const {
    const Level& level = levels_.back();
    for (const auto& entry : level.node) {
      const std::string key = entry.first.Scalar();
      if (std::find(level.taken.begin(), level.taken.end(), key) == level.taken.end()) {
        throw InputError("unknown option (config --dump lists every option)", file_,
                         entry.first.Mark().line + 1, path(key));
      }
    }
  }

 private:
  struct Level {
    YAML::Node node;
    std::string path;
    std::vector<std::string> taken{};
  };

  std::string path(std::string_view name) const {
    const std::string& prefix = levels_.back().path;
    return prefix.empty() ? std::string(name) : prefix + "." + std::string(name);
  }
  YAML::Node take(std::string_view name) {
    Level& level = levels_.back();
    level.taken.emplace_back(name);
    return level.node[std::string(name)];
  }
  std::optional<YAML::Node> scalar(std::string_view name, const char* what) {
    const YAML::Node node = take(name);
    if (!node.IsDefined())
      return std::nullopt;
    if (!node.IsScalar() || node.IsNull())
      fail(node, name, std::string("must be ") + what);
    return node;
  }
  double number(const YAML::Node& node, std::string_view name) const {
    const std::string& text = node.Scalar();
    if (text == ".inf" || text == "+.inf")
      return std::numeric_limits<double>::infinity();
    if (text == "-.inf")
      return -std::numeric_limits<double>::infinity();
    const char* begin = text.data() + (text.starts_with('+') ? 1 : 0);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size() || std::isnan(v))
      fail(node, name, "must be a number (got " + text + ")");
    return v;
  }
  /// `value` when it lies in the option's range, else InputError at `node`'s line.
  double in_range(double value, const YAML::Node& node, std::string_view name,
                  const OptionInfo& info, bool whole) const {
    // An option without a stated range takes any value of its type (the schema states one for
    // every option of a job: tests/io/options_schema_test.cpp).
    if (info.range && !info.range->contains(value))
      fail(node, name, "must be " + info.range->text(whole) + " (got " + node.Scalar() + ")");
    return value;
  }
  long long integer(const YAML::Node& node, std::string_view name) const {
    const std::string& text = node.Scalar();
    long long v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size())
      fail(node, name, "must be an integer (got " + text + ")");
    return v;
  }
  [[noreturn]] void fail(const YAML::Node& node, std::string_view name,
                         const std::string& message) const {
    throw InputError(message, file_, node.Mark().line >= 0 ? node.Mark().line + 1 : 0, path(name));
  }

  std::vector<Level> levels_;
  std::string file_;
};

}  // namespace

std::string options_yaml(const OptionTree& tree, const std::string& header) {
  YamlPrinter printer;
  if (!header.empty())
    printer.text = header;
  tree(printer);
  return printer.text;
}

std::string options_json(const OptionTree& tree) {
  JsonPrinter printer;
  tree(printer);
  return printer.root.dump(2) + "\n";
}

namespace {

/// Sets the options of `tree` that the document `root` of `where` gives.
void read_options(const YAML::Node& root, const std::string& where, const OptionTree& tree) {
  if (root.IsNull())
    return;  // an empty file changes nothing
  if (!root.IsMap())
    throw InputError("expected a YAML mapping of options", where, 1);
  YamlReader reader(root, where);
  tree(reader);
  reader.reject_unknown();
}

}  // namespace

void read_options_yaml(const std::filesystem::path& path, const OptionTree& tree) {
  read_options(load_yaml_file(path), path.string(), tree);
}

void read_options_yaml_text(const std::string& text, const std::string& source,
                            const OptionTree& tree) {
  read_options(load_yaml_text(text, source), source, tree);
}

}  // namespace floorgrid::io
