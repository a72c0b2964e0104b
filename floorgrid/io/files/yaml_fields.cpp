#include "floorgrid/io/files/yaml_fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/yaml_document.hpp"

namespace floorgrid::io {

namespace {

/// Parses a whole scalar as a finite double; YAML's own conversion accepts trailing garbage.
std::optional<double> parse_number(const std::string& text) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  while (begin < end && *begin == ' ')
    ++begin;
  if (begin < end && *begin == '+')
    ++begin;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value))
    return std::nullopt;
  return value;
}

}  // namespace

YamlFields::YamlFields(const std::filesystem::path& path) : path_(path) {
  node_ = load_yaml_file(path);
  if (!node_.IsMap()) {
    throw InputError(node_.IsNull() ? "empty YAML file" : "expected a YAML mapping of keys",
                     path.string(), 1);
  }
}

YamlFields::YamlFields(YAML::Node node, std::filesystem::path path, std::string prefix)
    : node_(std::move(node)), path_(std::move(path)), prefix_(std::move(prefix)) {}

bool YamlFields::has(const std::string& key) const {
  const YAML::Node value = node_[key];
  return value.IsDefined() && !value.IsNull();
}

long YamlFields::line_of(const std::string& key) const {
  const YAML::Node value = node_[key];
  if (value.IsDefined() && value.Mark().line >= 0)
    return value.Mark().line + 1;
  return node_.Mark().line >= 0 ? node_.Mark().line + 1 : 0;
}

void YamlFields::fail(const std::string& key, const std::string& message) const {
  throw InputError(message, path_.string(), line_of(key), prefix_ + key);
}

std::vector<std::pair<std::string, long>> YamlFields::unknown_keys(
    const std::vector<std::string>& known) const {
  std::vector<std::pair<std::string, long>> unknown;
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      unknown.emplace_back(key, entry.first.Mark().line + 1);
    }
  }
  return unknown;
}

void YamlFields::reject_unknown_keys(const std::vector<std::string>& known) const {
  const auto unknown = unknown_keys(known);
  if (!unknown.empty()) {
    std::string list;
    for (const auto& k : known)
      list += (list.empty() ? "" : ", ") + k;
    throw InputError("unknown key (known keys: " + list + ")", path_.string(),
                     unknown.front().second, prefix_ + unknown.front().first);
  }
}

double YamlFields::number(const std::string& key) const {
  const auto value = optional_number(key);
  if (!value)
    fail(key, "required key is missing");
  return *value;
}

std::optional<double> YamlFields::optional_number(const std::string& key) const {
  if (!has(key))
    return std::nullopt;
  const YAML::Node value = node_[key];
  if (!value.IsScalar())
    fail(key, "expected a number");
  const auto parsed = parse_number(value.Scalar());
  if (!parsed)
    fail(key, "expected a finite number (got '" + value.Scalar() + "')");
  return parsed;
}

std::string YamlFields::string(const std::string& key) const {
  const auto value = optional_string(key);
  if (!value)
    fail(key, "required key is missing");
  return *value;
}

std::optional<std::string> YamlFields::optional_string(const std::string& key) const {
  if (!has(key))
    return std::nullopt;
  const YAML::Node value = node_[key];
  if (!value.IsScalar())
    fail(key, "expected a text value");
  return value.Scalar();
}

std::optional<bool> YamlFields::optional_bool(const std::string& key) const {
  const auto text = optional_string(key);
  if (!text)
    return std::nullopt;
  if (*text == "0" || *text == "false" || *text == "False" || *text == "no")
    return false;
  if (*text == "1" || *text == "true" || *text == "True" || *text == "yes")
    return true;
  fail(key, "expected 0, 1, true or false (got '" + *text + "')");
}

std::optional<std::vector<double>> YamlFields::optional_numbers(const std::string& key,
                                                                std::size_t size) const {
  if (!has(key))
    return std::nullopt;
  const YAML::Node value = node_[key];
  if (!value.IsSequence())
    fail(key, "expected a list of numbers like [0.0, 0.0, 0.0]");
  if (size != 0 && value.size() != size) {
    fail(key, "expected " + std::to_string(size) + " numbers (got " + std::to_string(value.size()) +
                  ")");
  }
  std::vector<double> numbers;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const auto parsed = value[i].IsScalar() ? parse_number(value[i].Scalar()) : std::nullopt;
    if (!parsed)
      fail(key, "element " + std::to_string(i + 1) + " is not a finite number");
    numbers.push_back(*parsed);
  }
  return numbers;
}

std::optional<Pose2> YamlFields::optional_pose(const std::string& key) const {
  const auto numbers = optional_numbers(key, 3);
  if (!numbers)
    return std::nullopt;
  return Pose2{(*numbers)[0], (*numbers)[1], (*numbers)[2]};
}

std::optional<std::vector<std::string>> YamlFields::optional_strings(const std::string& key) const {
  if (!has(key))
    return std::nullopt;
  const YAML::Node value = node_[key];
  if (value.IsScalar())
    return std::vector<std::string>{value.Scalar()};
  if (!value.IsSequence())
    fail(key, "expected a list of text values");
  std::vector<std::string> out;
  for (const auto& item : value) {
    if (!item.IsScalar())
      fail(key, "expected a list of text values");
    out.push_back(item.Scalar());
  }
  return out;
}

std::optional<YamlFields> YamlFields::optional_map(const std::string& key) const {
  if (!has(key))
    return std::nullopt;
  const YAML::Node value = node_[key];
  if (!value.IsMap())
    fail(key, "expected a mapping of keys");
  return YamlFields(value, path_, prefix_ + key + ".");
}

}  // namespace floorgrid::io
