#pragma once

// cpp-httplib's <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen's headers
// included after it: include this header after any that bring Eigen.
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

#include "floorgrid/server/connection_limits.hpp"

namespace floorgrid::server {

/// One client connection as cpp-httplib's server reads and writes it (an httplib::Stream): the
/// request line and headers must come within header_timeout_s and max_header_bytes, a body
/// within body_timeout_s, each write progress within write_timeout_s; past a limit a read or
/// write fails and the connection is dropped. Handlers reach it with current() (they run on its
/// thread) to start the body's clock and to close the connection after their answer.
class HttpConnection final : public httplib::Stream {
 public:
  /// The connection on `socket` (closed by close()).
  HttpConnection(socket_t socket, const ConnectionLimits& limits);
  HttpConnection(const HttpConnection&) = delete;
  HttpConnection& operator=(const HttpConnection&) = delete;

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return socket_; }

  /// Waits up to idle_timeout_s for the next request's first byte; false when none came, the
  /// client closed, or `listening` became INVALID_SOCKET (the server stops).
  bool wait_for_request(const std::atomic<socket_t>& listening);
  /// A request starts: its line and headers are read from now on.
  void begin_request();
  /// The headers were read: the body (if any) is read from now on.
  void begin_body();
  /// Whether a read failed because its phase's time was up.
  bool timed_out() const { return timed_out_; }
  /// Whether the request line and headers went past max_header_bytes.
  bool headers_too_large() const { return headers_too_large_; }
  /// Closes the connection after this answer (its body was not read to the end).
  void close_after_answer() { close_after_answer_ = true; }
  /// Whether close_after_answer() was called.
  bool closing() const { return close_after_answer_; }
  /// Closes the socket. After close_after_answer(), first stops sending and reads what the
  /// client still sends for a moment (at most 1 s, 16 MiB), so that the client reads the
  /// answer before the connection resets.
  void close();

  /// The connection whose request this thread is answering (null outside one).
  static HttpConnection* current();

 private:
  friend class CurrentConnection;
  using Clock = std::chrono::steady_clock;
  /// Milliseconds left until `deadline`, at least 0.
  static int millis_until(Clock::time_point deadline);

  socket_t socket_;
  ConnectionLimits limits_;
  enum class Phase { headers, body } phase_ = Phase::headers;
  Clock::time_point deadline_;
  std::size_t header_bytes_ = 0;
  bool timed_out_ = false, headers_too_large_ = false, close_after_answer_ = false;
  bool closed_ = false;
  char buffer_[16384];
  std::size_t begin_ = 0, end_ = 0;  ///< bytes received and not yet read
};

/// cpp-httplib's server with each connection read and written through an HttpConnection; an
/// exception while answering drops that connection rather than the process.
class LimitedHttpServer : public httplib::Server {
 public:
  /// A server whose connections keep `limits`, and say so: the answers' Keep-Alive header
  /// gives the idle timeout they keep (whole seconds, rounded down), not cpp-httplib's 5 s. A
  /// client that believed 5 s reused connections closed after 2 (Node's fetch: "fetch failed").
  explicit LimitedHttpServer(const ConnectionLimits& limits);

 private:
  bool process_and_close_socket(socket_t socket) override;
  ConnectionLimits limits_;
};

}  // namespace floorgrid::server
