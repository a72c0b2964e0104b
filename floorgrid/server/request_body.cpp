#include "floorgrid/server/request_body.hpp"

#include <charconv>

#include "floorgrid/server/request_error.hpp"

namespace floorgrid::server {

std::optional<std::size_t> body_length(const httplib::Request& req) {
  if (!req.has_header("Content-Length"))
    return std::nullopt;
  const std::string text = req.get_header_value("Content-Length");
  std::size_t length = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), length);
  if (error != std::errc() || end != text.data() + text.size())
    throw RequestError(400, "Content-Length must be a number of bytes");
  return length;
}

namespace {

std::string too_large(std::size_t limit) {
  const std::string size = limit % (1u << 20) == 0   ? std::to_string(limit >> 20) + " MiB"
                           : limit % (1u << 10) == 0 ? std::to_string(limit >> 10) + " KiB"
                                                     : std::to_string(limit) + " bytes";
  return "the request body is over " + size + " (the limit of this route)";
}

}  // namespace

void close_after(httplib::Response& res) {
  if (HttpConnection* connection = HttpConnection::current())
    connection->close_after_answer();
  res.set_header("Connection", "close");
}

bool drop_body(const httplib::Request& req, httplib::Response& res,
               const httplib::ContentReader& reader, std::size_t drained_max) {
  const std::optional<std::size_t> length = body_length(req);
  if (!length || *length > drained_max) {
    close_after(res);
    return false;
  }
  // cpp-httplib drops a body over its own payload limit itself (reading it) and says false:
  // the connection then closes, with nothing left to read.
  std::size_t dropped = 0;
  const bool whole = reader([&](const char*, std::size_t n) {
    dropped += n;
    return true;
  });
  if (whole && dropped == *length)
    return true;
  close_after(res);
  return false;
}

std::string read_body(const httplib::Request& req, httplib::Response& res,
                      const httplib::ContentReader& reader, std::size_t limit,
                      std::size_t drained_max) {
  if (req.is_multipart_form_data()) {
    // cpp-httplib would parse it into parts, which no route takes.
    drop_body(req, res, reader, drained_max);
    throw RequestError(415, "a multipart body: send JSON (Content-Type: application/json)");
  }
  std::string body;
  if (const std::optional<std::size_t> length = body_length(req)) {
    if (*length > limit) {
      drop_body(req, res, reader, drained_max);
      throw RequestError(413, too_large(limit));
    }
    body.reserve(*length);
  }
  bool over = false;
  const bool whole = reader([&](const char* data, std::size_t n) {
    if (body.size() + n > limit) {
      over = true;
      return false;
    }
    body.append(data, n);
    return true;
  });
  if (!whole) {
    close_after(res);
    if (over)
      throw RequestError(413, too_large(limit));
    const HttpConnection* connection = HttpConnection::current();
    if (connection != nullptr && connection->timed_out())
      throw RequestError(408, "the request body did not come in time");
    throw RequestError(400, "the request body ended early (a broken chunk or connection)");
  }
  return body;
}

}  // namespace floorgrid::server
