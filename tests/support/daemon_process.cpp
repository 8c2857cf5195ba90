#include "daemon_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace rotord::testing {

int free_port() {
  // Free on every address, IPv6 and IPv4 (a dual-stack socket), as a daemon
  // started with --bind :: needs it: a port free on 127.0.0.1 alone may be
  // held on another loopback address by a test's client.
  int fd6 = ::socket(AF_INET6, SOCK_STREAM, 0);
  if (fd6 >= 0) {
    int v6only = 0;
    ::setsockopt(fd6, IPPROTO_IPV6, IPV6_V6ONLY, &v6only, sizeof v6only);
    sockaddr_in6 any{};
    any.sin6_family = AF_INET6;
    any.sin6_addr = in6addr_any;
    socklen_t len6 = sizeof(any);
    const bool ok = ::bind(fd6, reinterpret_cast<sockaddr*>(&any), sizeof(any)) == 0 &&
                    ::getsockname(fd6, reinterpret_cast<sockaddr*>(&any), &len6) == 0;
    ::close(fd6);
    if (ok) return ntohs(any.sin6_port);
  }
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr));
  socklen_t len = sizeof(addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

DaemonProcess::DaemonProcess(std::vector<std::string> extra_args) {
  // Each daemon gets its own settings directory, so tests never share saved
  // settings with each other or with the user running them (~/.config).
  char config_home[] = "/tmp/rotord-test-XXXXXX";
  if (::mkdtemp(config_home) != nullptr) config_home_ = config_home;
  // A port found free can be taken by a test running in parallel before the
  // daemon binds it: then start again on other ports.
  for (int attempt = 0; attempt < 5; ++attempt) {
    if (spawn(extra_args)) return;
    if (output_.find("Address already in use") == std::string::npos || attempt == 4) return;
    output_.clear();
  }
}

bool DaemonProcess::spawn(const std::vector<std::string>& extra_args) {
  ports_ = {free_port(), free_port(), free_port(), free_port(), free_port()};
  std::vector<std::string> args = {ROTORD_BINARY,
                                   "--wrc-port",
                                   std::to_string(ports_.wrc),
                                   "--rotctld-port",
                                   std::to_string(ports_.rotctld),
                                   "--web-port",
                                   std::to_string(ports_.web),
                                   "--gs232-port",
                                   std::to_string(ports_.gs232),
                                   "--easycomm-port",
                                   std::to_string(ports_.easycomm)};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  // Loopback only, unless the test names its own address (the default, ::,
  // serves IPv6 and IPv4).
  if (std::find(extra_args.begin(), extra_args.end(), "--bind") == extra_args.end()) {
    args.push_back("--bind");
    args.push_back("127.0.0.1");
  }
  for (int* fd : {&out_fd_, &in_fd_}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
  int pipe_fds[2];
  int in_fds[2];
  // Close-on-exec: a daemon started later by the same test must not hold
  // this one's pipes open (dup2 below clears the flag on the child's copies).
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return false;
  if (::pipe2(in_fds, O_CLOEXEC) != 0) return false;
  pid_ = ::fork();
  if (pid_ == 0) {
    ::dup2(in_fds[0], 0);
    ::dup2(pipe_fds[1], 1);
    ::dup2(pipe_fds[1], 2);
    ::close(pipe_fds[0]);
    ::close(in_fds[1]);
    if (!config_home_.empty()) ::setenv("XDG_CONFIG_HOME", config_home_.c_str(), 1);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  ::close(in_fds[0]);
  out_fd_ = pipe_fds[0];
  in_fd_ = in_fds[1];
  ::fcntl(out_fd_, F_SETFL, O_NONBLOCK);
  // Ready when it says so, or not when the process died.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    read_output(100);
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      read_output(0);
      return false;
    }
    // "ready" in either --log-format.
    if (output_.find("rotord: ready") != std::string::npos ||
        output_.find("\"msg\":\"ready\"") != std::string::npos) {
      ready_ = true;
      return true;
    }
  }
  return false;
}

void DaemonProcess::read_output(int timeout_ms) {
  if (out_fd_ < 0) return;
  pollfd p{out_fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return;
  char buf[4096];
  for (;;) {
    ssize_t n = ::read(out_fd_, buf, sizeof(buf));
    if (n <= 0) break;
    output_.append(buf, static_cast<std::size_t>(n));
  }
}

bool DaemonProcess::wait_for_output(const std::string& text, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (output_.find(text) == std::string::npos) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    read_output(50);
  }
  return true;
}

long long DaemonProcess::advance_ms(long long ms) {
  if (pid_ <= 0 || in_fd_ < 0) return -1;
  const std::string command = "advance " + std::to_string(ms) + "\n";
  if (::write(in_fd_, command.data(), command.size()) != static_cast<ssize_t>(command.size()))
    return -1;
  static const std::string kReply = "rotord: clock ";
  // Bounded for liveness only: a day of simulated time runs in seconds.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto at = output_.find(kReply, clock_seen_);
    const auto eol = at == std::string::npos ? at : output_.find('\n', at);
    if (eol != std::string::npos) {
      clock_seen_ = eol;
      return std::atoll(output_.c_str() + at + kReply.size());
    }
    read_output(100);
  }
  return -1;
}

void DaemonProcess::close_output() {
  if (out_fd_ >= 0) ::close(out_fd_);
  out_fd_ = -1;
}

int DaemonProcess::stop_with(int signal) {
  if (pid_ <= 0) return -1;
  ::kill(pid_, signal);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    read_output(20);
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      read_output(0);
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    ::usleep(10000);  // the pipe may be at EOF already, so poll returns at once
  }
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, &status, 0);
  pid_ = -1;
  return -1;
}

DaemonProcess::~DaemonProcess() {
  terminate();
  if (out_fd_ >= 0) ::close(out_fd_);
  if (in_fd_ >= 0) ::close(in_fd_);
  std::error_code ignored;
  if (!config_home_.empty()) std::filesystem::remove_all(config_home_, ignored);
}

TcpClient::TcpClient(int port) : TcpClient(port, "") {}

TcpClient::TcpClient(int port, const std::string& source) {
  if (source.find(':') != std::string::npos) {
    connect_ipv6(port, source);
    return;
  }
  fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (!source.empty()) {
    sockaddr_in local{};
    local.sin_family = AF_INET;
    if (::inet_pton(AF_INET, source.c_str(), &local.sin_addr) != 1 ||
        ::bind(fd_, reinterpret_cast<sockaddr*>(&local), sizeof(local)) != 0) {
      ::close(fd_);
      fd_ = -1;
      return;
    }
  }
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<uint16_t>(port));
  if (::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    ::close(fd_);
    fd_ = -1;
    return;
  }
  int one = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
}

void TcpClient::connect_ipv6(int port, const std::string& source) {
  fd_ = ::socket(AF_INET6, SOCK_STREAM, 0);
  sockaddr_in6 local{};
  local.sin6_family = AF_INET6;
  sockaddr_in6 addr{};
  addr.sin6_family = AF_INET6;
  addr.sin6_addr = in6addr_loopback;
  addr.sin6_port = htons(static_cast<uint16_t>(port));
  if (fd_ < 0 || ::inet_pton(AF_INET6, source.c_str(), &local.sin6_addr) != 1 ||
      ::bind(fd_, reinterpret_cast<sockaddr*>(&local), sizeof(local)) != 0 ||
      ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return;
  }
  int one = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
}

bool ipv6_loopback() {
  const int fd = ::socket(AF_INET6, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in6 addr{};
  addr.sin6_family = AF_INET6;
  addr.sin6_addr = in6addr_loopback;
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0;
  ::close(fd);
  return ok;
}

TcpClient::~TcpClient() {
  if (fd_ >= 0) ::close(fd_);
}

bool TcpClient::send(const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

namespace {
/// The milliseconds from now until `deadline` (not above 0 once passed).
long long ms_left(std::chrono::steady_clock::time_point deadline) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(deadline -
                                                               std::chrono::steady_clock::now())
      .count();
}
}  // namespace

bool TcpClient::read_line(std::string& line, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    auto lf = buffer_.find('\n');
    if (lf != std::string::npos) {
      line = buffer_.substr(0, lf);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      buffer_.erase(0, lf + 1);
      return true;
    }
    if (receive(ms_left(deadline)) != Received::bytes) return false;
  }
}

std::string TcpClient::recv_once(int timeout_ms) {
  if (!buffer_.empty()) {
    std::string out;
    out.swap(buffer_);
    return out;
  }
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return {};
  char buf[65536];
  ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
  if (n <= 0) return {};
  return std::string(buf, static_cast<std::size_t>(n));
}

bool TcpClient::wait_closed(int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const Received r = receive(ms_left(deadline));
    if (r != Received::bytes) return r == Received::closed;
  }
}

TcpClient::Received TcpClient::receive(long long timeout_ms) {
  if (timeout_ms <= 0) return Received::timeout;
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(timeout_ms)) <= 0) return Received::timeout;
  char buf[4096];
  const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
  if (n <= 0) return Received::closed;
  buffer_.append(buf, static_cast<std::size_t>(n));
  return Received::bytes;
}

bool TcpClient::closed_now() {
  if (fd_ < 0) return true;
  pollfd p{fd_, POLLIN, 0};
  while (::poll(&p, 1, 0) > 0) {
    char buf[4096];
    const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
    if (n <= 0) return true;
    buffer_.append(buf, static_cast<std::size_t>(n));
  }
  return false;
}

std::string TcpClient::ask(const std::string& command, int timeout_ms) {
  std::string line;
  if (!send(command)) return "<send failed>";
  if (!read_line(line, timeout_ms)) return "<no reply>";
  return line;
}

}  // namespace rotord::testing
