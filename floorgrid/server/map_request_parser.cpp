#include "floorgrid/server/map_request_parser.hpp"

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid::server {

namespace {

/// A value as an error message repeats it: JSON text, cut short.
std::string shown(std::string text) {
  constexpr std::size_t kMaxShown = 80;
  if (text.size() > kMaxShown)
    text = text.substr(0, kMaxShown) + "...";
  return text;
}

/// A scalar value of the body: its JSON text, and its number or string when it is one.
struct Scalar {
  std::string text;
  bool is_number = false;
  double number = 0.0;
  const std::string* string = nullptr;  ///< a string's value (valid during the event)
};

/// A top-level field's value, kept when it is a short scalar.
struct Field {
  bool given = false;
  std::string text;                   ///< JSON text ("a list", "an object" for containers)
  std::optional<std::string> string;  ///< its value when it is a string
};

/// The body's SAX events (nlohmann::json::sax_parse) to a MapRequest. Every error is noted,
/// the first of each kind kept, and the body read to its end: whether it is JSON at all decides
/// first, as it does for a body parsed whole.
class MapRequestReader {
 public:
  MapRequestReader(const RequestLimits& limits, std::size_t body_bytes) : limits_(limits) {
    // A point takes at least 6 bytes ("[1,2],"): room for all without a regrowth.
    points_.reserve(std::min(limits.max_points, body_bytes / 6 + 1));
  }

  bool null() { return scalar({"null"}); }
  bool boolean(bool value) { return scalar({value ? "true" : "false"}); }
  bool number_integer(std::int64_t value) {
    return scalar({std::to_string(value), true, static_cast<double>(value)});
  }
  bool number_unsigned(std::uint64_t value) {
    return scalar({std::to_string(value), true, static_cast<double>(value)});
  }
  bool number_float(double value, const std::string& text) { return scalar({text, true, value}); }
  bool string(std::string& value) {
    return scalar({nlohmann::json(value).dump(), false, 0.0, &value});
  }
  bool binary(nlohmann::json::binary_t&) { return scalar({"binary"}); }
  bool start_object(std::size_t) { return open(false); }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(true); }
  bool end_array() { return close(); }
  bool key(std::string& name) {
    if (skip_from_ == 0 && depth_ == 1) {
      key_ = name;
      if (key_ == "points" && points_given_)
        note(points_error_, "'points' is given twice");
    }
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) {
    not_json_ = true;
    return false;
  }

  /// The request, or the first error by the order of map_points: JSON, object, 'from',
  /// 'model', 'points'.
  MapRequest result(const std::string& served_model) {
    if (not_json_)
      throw RequestError(400, "the body is not JSON");
    if (!object_)
      throw RequestError(400, "the body must be a JSON object");
    if (!from_.given)
      throw RequestError(400, "'from' is missing");
    if (from_.string != "plan" && from_.string != "grid")
      throw RequestError(400,
                         "'from' must be \"plan\" or \"grid\" (got " + shown(from_.text) + ")");
    if (model_.given && model_.string != served_model) {
      throw RequestError(400, "'model': this session maps with '" + served_model + "' (got " +
                                  shown(model_.text) + ")");
    }
    if (!points_given_)
      throw RequestError(400, "'points' is missing");
    if (points_error_)
      throw RequestError(400, *points_error_);
    if (count_ > limits_.max_points) {
      throw RequestError(413, "'points' holds " + std::to_string(count_) + " points; at most " +
                                  std::to_string(limits_.max_points) + " per request");
    }
    if (point_error_)
      throw RequestError(400, *point_error_);
    MapRequest request;
    request.forward = from_.string == "plan";
    request.points = std::move(points_);
    return request;
  }

 private:
  static void note(std::optional<std::string>& first, std::string message) {
    if (!first)
      first = std::move(message);
  }

  /// Skips the container just opened (and all inside it).
  bool skip() {
    skip_from_ = ++depth_;
    return true;
  }

  std::string where() const { return "'points[" + std::to_string(count_ - 1) + "]'"; }

  void keep(Field& field, const std::string& text, const std::string* string) {
    field.given = true;
    field.text = text;
    field.string.reset();
    if (string != nullptr)
      field.string = *string;
  }

  bool open(bool array) {
    if (skip_from_ != 0) {
      ++depth_;
      return true;
    }
    switch (depth_) {
      case 0:
        object_ = !array;
        if (array)
          return skip();
        depth_ = 1;
        return true;
      case 1:  // the value of a top-level field
        if (key_ == "points") {
          points_given_ = true;
          if (!array) {
            note(points_error_, "'points' must be a list of [x, y] or [x, y, theta]");
            return skip();
          }
          depth_ = 2;
          return true;
        }
        if (key_ == "from")
          keep(from_, array ? "a list" : "an object", nullptr);
        if (key_ == "model")
          keep(model_, array ? "a list" : "an object", nullptr);
        return skip();
      case 2:  // a point
        ++count_;
        coordinates_ = 0;
        coordinate_error_.reset();
        point_ = RequestPoint{};
        if (!array) {
          note(point_error_, where() + " must be [x, y] or [x, y, theta]");
          return skip();
        }
        depth_ = 3;
        return true;
      default:  // a coordinate that is a list or an object
        coordinate(Scalar{array ? "a list" : "an object"});
        return skip();
    }
  }

  bool close() {
    --depth_;
    if (skip_from_ != 0) {
      if (depth_ < skip_from_)
        skip_from_ = 0;
      return true;
    }
    if (depth_ == 2) {  // a point ended
      if (coordinates_ < 2 || coordinates_ > 3) {
        note(point_error_, where() + " must be [x, y] or [x, y, theta]");
      } else if (coordinate_error_) {
        note(point_error_, *coordinate_error_);
      } else if (!point_error_ && count_ <= limits_.max_points) {
        point_.has_theta = coordinates_ == 3;
        points_.push_back(point_);
      }
    }
    return true;
  }

  bool scalar(const Scalar& value) {
    if (skip_from_ != 0)
      return true;
    switch (depth_) {
      case 0:
        object_ = false;
        return true;
      case 1:
        if (key_ == "from")
          keep(from_, value.text, value.string);
        else if (key_ == "model")
          keep(model_, value.text, value.string);
        else if (key_ == "points") {
          points_given_ = true;
          note(points_error_, "'points' must be a list of [x, y] or [x, y, theta]");
        }
        return true;
      case 2:
        ++count_;
        note(point_error_, where() + " must be [x, y] or [x, y, theta]");
        return true;
      default:
        coordinate(value);
        return true;
    }
  }

  /// The next coordinate of the point being read.
  void coordinate(const Scalar& value) {
    const int index = coordinates_++;
    if (index > 2 || coordinate_error_)
      return;  // too many: said when the point ends
    static const char* const kNames[] = {"x", "y", "theta"};
    const std::string name = where() + " " + kNames[index];
    if (!value.is_number) {
      coordinate_error_ = name + " must be a number (got " + shown(value.text) + ")";
      return;
    }
    // The parser refuses numbers beyond double's range; a heading may be any finite angle.
    if (index < 2 && !(std::abs(value.number) <= kMaxCoordinate)) {
      coordinate_error_ = name + " must be within 1e7 m of the origin (got " + shown(value.text) +
                          "): not a coordinate in a building";
      return;
    }
    double* const target[] = {&point_.pose.x, &point_.pose.y, &point_.pose.theta};
    *target[index] = value.number;
  }

  const RequestLimits& limits_;
  int depth_ = 0;      ///< containers open
  int skip_from_ = 0;  ///< skipping the containers from this depth on (0: not)
  bool not_json_ = false, object_ = false, points_given_ = false;
  std::string key_;
  Field from_, model_;
  std::optional<std::string> points_error_, point_error_, coordinate_error_;
  std::size_t count_ = 0;  ///< points seen, kept or not
  int coordinates_ = 0;    ///< of the point being read
  RequestPoint point_;
  std::vector<RequestPoint> points_;
};

}  // namespace

MapRequest parse_map_request(std::string_view body, const RequestLimits& limits,
                             const std::string& served_model) {
  MapRequestReader reader(limits, body.size());
  nlohmann::json::sax_parse(body.begin(), body.end(), &reader);
  return reader.result(served_model);
}

}  // namespace floorgrid::server
