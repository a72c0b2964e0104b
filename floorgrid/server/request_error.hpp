#pragma once

#include <stdexcept>
#include <string>

namespace floorgrid::server {

/// A request the API refuses: the HTTP status (400 bad request, 413 too large, 503 busy...) and a
/// message naming the field.
class RequestError : public std::runtime_error {
 public:
  /// An error answered with `status` and `message`.
  RequestError(int status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  /// The HTTP status to answer with.
  int status() const { return status_; }

 private:
  int status_;
};

}  // namespace floorgrid::server
