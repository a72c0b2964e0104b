#include "floorgrid/server/http_connection.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

namespace floorgrid::server {

namespace {

thread_local HttpConnection* current_connection = nullptr;

/// Waits up to `millis` for `events` on `socket`: > 0 ready (or closed), 0 timed out, < 0 error.
int wait_for(socket_t socket, short events, int millis) {
  for (;;) {
    pollfd p{socket, events, 0};
    const int ready = ::poll(&p, 1, millis);
    if (ready < 0 && errno == EINTR)
      continue;
    return ready;
  }
}

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1000.0));
}

void address_of(const sockaddr_storage& address, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto& a = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof(text));
    port = ntohs(a.sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto& a = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &a.sin6_addr, text, sizeof(text));
    port = ntohs(a.sin6_port);
  }
  ip = text;
}

}  // namespace

/// Makes a connection this thread's current() while it lives.
class CurrentConnection {
 public:
  explicit CurrentConnection(HttpConnection& connection) { current_connection = &connection; }
  ~CurrentConnection() { current_connection = nullptr; }
  CurrentConnection(const CurrentConnection&) = delete;
  CurrentConnection& operator=(const CurrentConnection&) = delete;
};

HttpConnection::HttpConnection(socket_t socket, const ConnectionLimits& limits)
    : socket_(socket), limits_(limits) {
  begin_request();
}

HttpConnection* HttpConnection::current() {
  return current_connection;
}

int HttpConnection::millis_until(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return static_cast<int>(std::clamp<long long>(left.count(), 0, 1 << 30));
}

void HttpConnection::begin_request() {
  phase_ = Phase::headers;
  header_bytes_ = 0;
  deadline_ = Clock::now() + millis(limits_.header_timeout_s);
}

void HttpConnection::begin_body() {
  phase_ = Phase::body;
  deadline_ = Clock::now() + millis(limits_.body_timeout_s);
}

bool HttpConnection::wait_for_request(const std::atomic<socket_t>& listening) {
  if (begin_ < end_)
    return true;  // the next request came with the last one
  const Clock::time_point deadline = Clock::now() + millis(limits_.idle_timeout_s);
  for (;;) {
    if (listening == INVALID_SOCKET)
      return false;
    const int left = millis_until(deadline);
    // In slices, so that a stopping server is noticed.
    const int ready = wait_for(socket_, POLLIN, std::min(left, 100));
    if (ready != 0)
      return ready > 0;
    if (left == 0)
      return false;
  }
}

bool HttpConnection::is_readable() const {
  return begin_ < end_ || wait_for(socket_, POLLIN, millis_until(deadline_)) > 0;
}

bool HttpConnection::is_writable() const {
  return wait_for(socket_, POLLOUT, static_cast<int>(millis(limits_.write_timeout_s).count())) > 0;
}

ssize_t HttpConnection::read(char* ptr, size_t size) {
  if (phase_ == Phase::headers && header_bytes_ >= limits_.max_header_bytes) {
    headers_too_large_ = true;
    return -1;
  }
  while (begin_ == end_) {
    const int left = millis_until(deadline_);
    if (left == 0) {
      timed_out_ = true;
      return -1;
    }
    const int ready = wait_for(socket_, POLLIN, left);
    if (ready < 0)
      return -1;
    if (ready == 0)
      continue;  // the deadline decides
    const ssize_t n = ::recv(socket_, buffer_, sizeof(buffer_), 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN))
      continue;
    if (n <= 0)
      return n;
    begin_ = 0;
    end_ = static_cast<std::size_t>(n);
  }
  std::size_t n = std::min(size, end_ - begin_);
  if (phase_ == Phase::headers)
    n = std::min(n, limits_.max_header_bytes - header_bytes_);
  std::memcpy(ptr, buffer_ + begin_, n);
  begin_ += n;
  if (phase_ == Phase::headers)
    header_bytes_ += n;
  return static_cast<ssize_t>(n);
}

ssize_t HttpConnection::write(const char* ptr, size_t size) {
  for (;;) {
    if (!is_writable())
      return -1;  // the client took nothing for write_timeout_s
    const ssize_t n = ::send(socket_, ptr, size, MSG_NOSIGNAL);
    if (n < 0 && (errno == EINTR || errno == EAGAIN))
      continue;
    return n;
  }
}

void HttpConnection::get_remote_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  if (::getpeername(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0)
    address_of(address, ip, port);
}

void HttpConnection::get_local_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof(address);
  if (::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0)
    address_of(address, ip, port);
}

void HttpConnection::close() {
  if (closed_)
    return;
  closed_ = true;
  if (close_after_answer_) {
    // A close with unread bytes resets the connection, and the client may lose the answer
    // with it: stop sending, then take what comes for a moment.
    ::shutdown(socket_, SHUT_WR);
    const Clock::time_point deadline = Clock::now() + std::chrono::seconds(1);
    std::size_t drained = 0;
    while (drained < (16u << 20) && wait_for(socket_, POLLIN, millis_until(deadline)) > 0) {
      const ssize_t n = ::recv(socket_, buffer_, sizeof(buffer_), 0);
      if (n <= 0)
        break;
      drained += static_cast<std::size_t>(n);
    }
  }
  ::shutdown(socket_, SHUT_RDWR);
  ::close(socket_);
}

LimitedHttpServer::LimitedHttpServer(const ConnectionLimits& limits) : limits_(limits) {
  set_keep_alive_timeout(static_cast<time_t>(std::floor(std::max(0.0, limits.idle_timeout_s))));
}

bool LimitedHttpServer::process_and_close_socket(socket_t socket) {
  HttpConnection connection(socket, limits_);
  const CurrentConnection scope(connection);
  bool answered = false;
  for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
    if (!connection.wait_for_request(svr_sock_))
      break;
    connection.begin_request();
    bool client_closes = false;
    try {
      answered = process_request(connection, left == 1, client_closes, nullptr);
    } catch (...) {
      // An answer that could not be written (the handlers' own exceptions are answered 500
      // by cpp-httplib): drop this connection, keep the server.
      answered = false;
    }
    if (!answered || client_closes || connection.closing() || connection.timed_out() ||
        connection.headers_too_large())
      break;
  }
  connection.close();
  return answered;
}

}  // namespace floorgrid::server
