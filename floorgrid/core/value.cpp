#include "floorgrid/core/value.hpp"

#include <cassert>
#include <limits>

namespace floorgrid {

Value::Value(const std::vector<std::string>& texts) : data_(Array{}) {
  Array& items = std::get<Array>(data_);
  for (const std::string& t : texts)
    items.emplace_back(t);
}

Value Value::array(std::initializer_list<Value> items) {
  Value v;
  v.data_ = Array(items);
  return v;
}

Value Value::object() {
  Value v;
  v.data_ = Object{};
  return v;
}

double Value::as_number() const {
  if (const auto* i = std::get_if<std::int64_t>(&data_))
    return static_cast<double>(*i);
  if (const auto* u = std::get_if<std::uint64_t>(&data_))
    return static_cast<double>(*u);
  return std::get<double>(data_);
}

bool Value::as_integer(std::int64_t& out) const {
  if (const auto* i = std::get_if<std::int64_t>(&data_)) {
    out = *i;
    return true;
  }
  if (const auto* u = std::get_if<std::uint64_t>(&data_)) {
    if (*u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      return false;
    out = static_cast<std::int64_t>(*u);
    return true;
  }
  return false;
}

std::size_t Value::size() const {
  if (is_array())
    return items().size();
  if (is_object())
    return members().size();
  return 0;
}

const Value* Value::find(std::string_view key) const {
  if (!is_object())
    return nullptr;
  for (const Member& m : members()) {
    if (m.first == key)
      return &m.second;
  }
  return nullptr;
}

Value& Value::operator[](std::string_view key) {
  if (is_null())
    data_ = Object{};
  assert(is_object());
  Object& object = std::get<Object>(data_);
  for (Member& m : object) {
    if (m.first == key)
      return m.second;
  }
  object.emplace_back(std::string(key), Value());
  return object.back().second;
}

void Value::push_back(Value item) {
  if (is_null())
    data_ = Array{};
  assert(is_array());
  std::get<Array>(data_).push_back(std::move(item));
}

}  // namespace floorgrid
