#include "floorgrid/io/files/value_json.hpp"

#include <algorithm>
#include <set>
#include <variant>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/overloaded.hpp"

namespace floorgrid::io {

namespace {

long line_at(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<long>(std::count(
                 text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

/// The deepest nesting of arrays and objects in `text` (outside strings), and where it first
/// passes `limit` (npos when it does not).
std::size_t first_too_deep(const std::string& text, int limit) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit)
        return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

/// Where the `index`-th (0-based) object key of `text` starts: a string followed by ':'.
std::size_t key_offset(const std::string& text, std::size_t index) {
  std::size_t keys = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '"')
      continue;
    const std::size_t start = i;
    for (++i; i < text.size() && text[i] != '"'; ++i) {
      if (text[i] == '\\')
        ++i;
    }
    std::size_t after = i + 1;
    while (after < text.size() && (text[after] == ' ' || text[after] == '\t' ||
                                   text[after] == '\n' || text[after] == '\r'))
      ++after;
    if (after < text.size() && text[after] == ':' && keys++ == index)
      return start;
  }
  return text.size();
}

/// The JSON library's message without its "[json.exception.parse_error.101] " tag.
std::string reason(const nlohmann::json::exception& e) {
  std::string text = e.what();
  if (text.starts_with("[json.exception.")) {
    const std::size_t end = text.find("] ");
    if (end != std::string::npos)
      text.erase(0, end + 2);
  }
  return text;
}

}  // namespace

nlohmann::json to_json(const Value& value) {
  return std::visit(Overloaded{[](std::monostate) { return nlohmann::json(nullptr); },
                               [](bool b) { return nlohmann::json(b); },
                               [](std::int64_t i) { return nlohmann::json(i); },
                               [](std::uint64_t u) { return nlohmann::json(u); },
                               [](double d) { return nlohmann::json(d); },
                               [](const std::string& s) { return nlohmann::json(s); },
                               [](const Value::Array& items) {
                                 nlohmann::json out = nlohmann::json::array();
                                 for (const Value& item : items)
                                   out.push_back(to_json(item));
                                 return out;
                               },
                               [](const Value::Object& members) {
                                 nlohmann::json out = nlohmann::json::object();
                                 for (const auto& [key, item] : members)
                                   out[key] = to_json(item);
                                 return out;
                               }},
                    value.data());
}

Value from_json(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::boolean:
      return Value(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return Value(json.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return Value(json.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return Value(json.get<double>());
    case nlohmann::json::value_t::string:
      return Value(json.get<std::string>());
    case nlohmann::json::value_t::array: {
      Value out = Value::array();
      for (const nlohmann::json& item : json)
        out.push_back(from_json(item));
      return out;
    }
    case nlohmann::json::value_t::object: {
      Value out = Value::object();
      for (const auto& [key, item] : json.items())
        out[key] = from_json(item);
      return out;
    }
    default:
      return Value();
  }
}

nlohmann::json parse_json_document(const std::string& text, const std::string& where) {
  if (const std::size_t at = first_too_deep(text, kMaxJsonDepth); at != std::string::npos) {
    throw InputError("nested deeper than " + std::to_string(kMaxJsonDepth) + " levels", where,
                     line_at(text, at));
  }
  // The keys of each open object, to refuse one given twice.
  std::vector<std::set<std::string>> open_objects;
  std::size_t keys_seen = 0;
  const auto check_keys = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) {
      open_objects.emplace_back();
    } else if (event == Event::object_end) {
      open_objects.pop_back();
    } else if (event == Event::key) {
      const std::string& key = parsed.get_ref<const std::string&>();
      if (!open_objects.empty() && !open_objects.back().insert(key).second) {
        throw InputError("key given twice in one object (which one counts would be a guess)", where,
                         line_at(text, key_offset(text, keys_seen)), key);
      }
      ++keys_seen;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, check_keys);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError("not valid JSON: " + reason(e), where, line_at(text, e.byte));
  } catch (const nlohmann::json::exception& e) {
    throw InputError("not valid JSON: " + reason(e), where, 0);
  }
}

Value parse_json(const std::string& text, const std::string& where) {
  return from_json(parse_json_document(text, where));
}

std::string dump_json(const Value& value, int indent) {
  return to_json(value).dump(indent);
}

}  // namespace floorgrid::io
