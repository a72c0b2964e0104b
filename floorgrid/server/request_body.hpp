#pragma once

#include <cstddef>
#include <optional>
#include <string>

// Last: cpp-httplib's <httplib.h> (through http_connection.hpp) brings <resolv.h>, whose `_res`
// macro breaks Eigen's headers after it.
#include "floorgrid/server/http_connection.hpp"  // NOLINT(llvm-include-order)

namespace floorgrid::server {

/// The length the request's Content-Length declares (none without one); RequestError 400 when
/// it is not a number.
std::optional<std::size_t> body_length(const httplib::Request& req);

/// Closes the connection once `res` is sent (the request's body was not read to its end).
void close_after(httplib::Response& res);

/// The body of `req` read through `reader` (cpp-httplib reads a chunked body, or one without a
/// length, whole into memory itself: a route reads its own). RequestError 413 past `limit` bytes
/// in any transfer encoding (a declared length over it is read and dropped up to `drained_max`
/// bytes, so that the client reads the answer; the connection closes beyond), 408 when it does
/// not come within the connection's body timeout, 400 when it ends early, 415 when it is
/// multipart (no route takes form parts).
std::string read_body(const httplib::Request& req, httplib::Response& res,
                      const httplib::ContentReader& reader, std::size_t limit,
                      std::size_t drained_max = 64u << 20);

/// Reads the rest of the body of `req` and drops it, up to `drained_max` bytes; true when it was
/// read to its end (the connection can take the next request), else closes after the answer.
bool drop_body(const httplib::Request& req, httplib::Response& res,
               const httplib::ContentReader& reader, std::size_t drained_max = 64u << 20);

}  // namespace floorgrid::server
