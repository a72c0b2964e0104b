#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace floorgrid {

/// A tree of plain values with the shape of a JSON document but none of its text: what a
/// mapping model writes into its model file and reads back, free of any file format (io/ turns
/// it into JSON and back, and is where a file's syntax is checked).
class Value {
 public:
  using Array = std::vector<Value>;
  using Member = std::pair<std::string, Value>;
  using Object = std::vector<Member>;  ///< in insertion order; keys are unique

  Value() = default;                                                        ///< null
  Value(std::nullptr_t) {}                                                  ///< null
  Value(bool v) : data_(v) {}                                               ///< a boolean
  Value(int v) : data_(std::int64_t{v}) {}                                  ///< an integer
  Value(long v) : data_(std::int64_t{v}) {}                                 ///< an integer
  Value(long long v) : data_(std::int64_t{v}) {}                            ///< an integer
  Value(unsigned v) : data_(std::uint64_t{v}) {}                            ///< a count
  Value(unsigned long v) : data_(std::uint64_t{v}) {}                       ///< a count
  Value(unsigned long long v) : data_(std::uint64_t{v}) {}                  ///< a count
  Value(double v) : data_(v) {}                                             ///< a number
  Value(const char* v) : data_(std::string(v)) {}                           ///< a text
  Value(std::string v) : data_(std::move(v)) {}                             ///< a text
  Value(std::string_view v) : data_(std::string(v)) {}                      ///< a text
  Value(const std::vector<std::string>& texts);                             ///< a list of texts
  Value(std::initializer_list<Member> members) : data_(Object(members)) {}  ///< an object

  /// A list of values.
  static Value array(std::initializer_list<Value> items = {});
  /// An empty object.
  static Value object();

  bool is_null() const { return std::holds_alternative<std::monostate>(data_); }
  bool is_bool() const { return std::holds_alternative<bool>(data_); }
  /// An integer (signed or unsigned) or a floating-point number.
  bool is_number() const { return is_integer() || std::holds_alternative<double>(data_); }
  /// A number written without a fraction.
  bool is_integer() const {
    return std::holds_alternative<std::int64_t>(data_) ||
           std::holds_alternative<std::uint64_t>(data_);
  }
  bool is_string() const { return std::holds_alternative<std::string>(data_); }
  bool is_array() const { return std::holds_alternative<Array>(data_); }
  bool is_object() const { return std::holds_alternative<Object>(data_); }

  /// The boolean (is_bool() must hold).
  bool as_bool() const { return std::get<bool>(data_); }
  /// The number as a double (is_number() must hold).
  double as_number() const;
  /// Whether the value is an integer that fits an int64_t; then stores it in `out`.
  bool as_integer(std::int64_t& out) const;
  /// The text (is_string() must hold).
  const std::string& as_string() const { return std::get<std::string>(data_); }
  /// The items of an array (is_array() must hold).
  const Array& items() const { return std::get<Array>(data_); }
  /// The members of an object (is_object() must hold).
  const Object& members() const { return std::get<Object>(data_); }
  /// Items of an array or members of an object; 0 otherwise.
  std::size_t size() const;

  /// The member `key` of an object, or null when absent (or not an object).
  const Value* find(std::string_view key) const;
  /// The member `key`, added as null when absent; a null value becomes an empty object first.
  Value& operator[](std::string_view key);
  /// Appends to an array; a null value becomes an empty array first.
  void push_back(Value item);

  bool operator==(const Value& other) const = default;

  /// The raw alternatives, for converters (io/).
  using Data = std::variant<std::monostate, bool, std::int64_t, std::uint64_t, double, std::string,
                            Array, Object>;
  /// The alternative held.
  const Data& data() const { return data_; }

 private:
  Data data_;
};

}  // namespace floorgrid
