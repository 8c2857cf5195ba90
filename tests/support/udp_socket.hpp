#pragma once
// A UDP socket on 127.0.0.1 for the tests that talk to the daemon's UDP
// rotor protocols (N1MM+, PstRotator): real datagrams over the loopback.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <string>

namespace rotord::testing {

/// Bound to 127.0.0.1:port (0: any free port); closes itself.
class Udp {
 public:
  explicit Udp(int port = 0) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in a = loopback(port);
    bound_ = ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
    socklen_t len = sizeof(a);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~Udp() { ::close(fd_); }
  Udp(const Udp&) = delete;
  Udp& operator=(const Udp&) = delete;
  bool bound() const { return bound_; }
  int port() const { return port_; }
  void send_to(int port, const std::string& datagram) const {
    const sockaddr_in a = loopback(port);
    ::sendto(fd_, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&a),
             sizeof(a));
  }
  /// The next datagram, or "" after timeout_ms (liveness only).
  std::string receive(int timeout_ms = 5000) const {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) != 1) return "";
    char buf[1024];
    const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  }

 private:
  static sockaddr_in loopback(int port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    return a;
  }

  int fd_ = -1;
  int port_ = 0;
  bool bound_ = false;
};

}  // namespace rotord::testing
