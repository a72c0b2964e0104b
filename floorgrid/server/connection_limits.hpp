#pragma once

#include <cstddef>

namespace floorgrid::server {

/// How long and how much one connection may take to say what it wants. cpp-httplib 0.11's own
/// read timeout restarts at every byte (a header line every few seconds holds a thread for
/// ever) and it reads a chunked body, or one without a length, whole: HttpConnection keeps these
/// limits instead.
struct ConnectionLimits {
  double idle_timeout_s = 2.0;    ///< seconds to wait for a request's first byte
  double header_timeout_s = 5.0;  ///< seconds from a request's first byte to its headers' end
  std::size_t max_header_bytes = 64u << 10;  ///< request line and headers together, bytes
  double body_timeout_s = 30.0;              ///< seconds from the headers' end to the body's end
  double write_timeout_s = 10.0;  ///< seconds an answer may wait for the client to take more
};

}  // namespace floorgrid::server
