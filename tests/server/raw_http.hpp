// A client on a bare socket for the server's hostile-input tests: exact bytes out (no encoding,
// no framing done for it), the answer read back while counting rather than keeping it, and the
// process's own memory (the server runs in the test's process).
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>

namespace floorgrid::server::test {

/// A TCP connection to 127.0.0.1:port (closed when the object dies).
class RawConnection {
 public:
  explicit RawConnection(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~RawConnection() {
    if (fd_ >= 0)
      ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  /// Whether the connection was made.
  bool connected() const { return fd_ >= 0; }

  /// Sends all of `bytes`; false when the server closed the connection (or it broke).
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (n <= 0)
        return false;
      bytes.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }

  /// Whether the server closed the connection (or sent something) within `timeout`.
  bool readable_within(std::chrono::milliseconds timeout) const {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, static_cast<int>(timeout.count())) > 0;
  }

  /// Reads until the server closes or `timeout` passes without a byte; keeps the first
  /// `keep` bytes in head(), counts the rest and the occurrences of `count_of` in all.
  void read_all(std::chrono::milliseconds timeout, std::size_t keep = 1 << 16,
                std::string_view count_of = {}) {
    std::string tail;  // the end of the last block, so that a match across blocks is found
    char block[1 << 16];
    while (readable_within(timeout)) {
      const ssize_t n = ::recv(fd_, block, sizeof(block), 0);
      if (n <= 0)
        break;
      const std::string_view got(block, static_cast<std::size_t>(n));
      received_ += got.size();
      if (head_.size() < keep)
        head_.append(got.substr(0, std::min(got.size(), keep - head_.size())));
      if (!count_of.empty()) {
        const std::string text = tail + std::string(got);
        for (std::size_t at = text.find(count_of); at != std::string::npos;
             at = text.find(count_of, at + 1))
          ++count_;
        tail = text.substr(text.size() - std::min(text.size(), count_of.size() - 1));
      }
    }
  }

  /// The first bytes of the answer.
  const std::string& head() const { return head_; }
  /// Bytes received.
  std::size_t received() const { return received_; }
  /// Occurrences of read_all's `count_of`.
  std::size_t count() const { return count_; }
  /// The status of the answer in head() (0: none).
  int status() const {
    int status = 0;
    return std::sscanf(head_.c_str(), "HTTP/1.%*d %d", &status) == 1 ? status : 0;
  }
  /// The body of an answer in head() that is not chunked.
  std::string body() const {
    const std::size_t at = head_.find("\r\n\r\n");
    return at == std::string::npos ? std::string() : head_.substr(at + 4);
  }

 private:
  int fd_ = -1;
  std::string head_;
  std::size_t received_ = 0;
  std::size_t count_ = 0;
};

/// One request on a new connection, the whole answer read (up to 10 s without a byte).
inline RawConnection& exchange(RawConnection& connection, std::string_view request) {
  connection.send(request);
  connection.read_all(std::chrono::seconds(10));
  return connection;
}

/// This process's resident memory ("VmRSS") or its peak ("VmHWM"), bytes.
inline std::size_t memory_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.starts_with(field + ":"))
      return std::stoull(line.substr(field.size() + 1)) * 1024;
  }
  return 0;
}

/// Resets this process's peak resident memory to what it holds now (Linux: clear_refs 5).
inline void reset_memory_peak() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

}  // namespace floorgrid::server::test
