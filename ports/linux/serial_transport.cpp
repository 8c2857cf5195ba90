#include "serial_transport.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "log.hpp"

namespace rotord::linux_port {
namespace {

std::string errno_text() {
  return std::strerror(errno);
}

/// Raw 8N1, no flow control, no echo, no CR/LF translation: every byte the
/// client sends reaches the session as it is.
bool make_raw(int fd, std::optional<unsigned> speed, std::string& error) {
  termios t{};
  if (::tcgetattr(fd, &t) != 0) {
    error = "tcgetattr: " + errno_text();
    return false;
  }
  ::cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS);
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cc[VMIN] = 1;
  t.c_cc[VTIME] = 0;
  if (speed) {
    ::cfsetispeed(&t, static_cast<speed_t>(*speed));
    ::cfsetospeed(&t, static_cast<speed_t>(*speed));
  }
  if (::tcsetattr(fd, TCSANOW, &t) != 0) {
    error = "tcsetattr: " + errno_text();
    return false;
  }
  return true;
}

}  // namespace

std::optional<unsigned> termios_speed(int baud) {
  switch (baud) {
    case 1200:
      return B1200;
    case 2400:
      return B2400;
    case 4800:
      return B4800;
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    default:
      return std::nullopt;
  }
}

std::optional<SerialSpec> parse_serial_spec(const std::string& text, bool pty, std::string& error) {
  SerialSpec spec;
  spec.pty = pty;
  const std::size_t colon = text.find(':');
  spec.personality = text.substr(0, colon);
  if (spec.personality.empty()) {
    error = "'" + text + "': the personality is missing";
    return std::nullopt;
  }
  if (pty) {
    if (colon != std::string::npos) spec.path = text.substr(colon + 1);
    if (colon != std::string::npos && spec.path.empty()) {
      error = "'" + text + "': the link path after ':' is empty";
      return std::nullopt;
    }
    return spec;
  }
  if (colon == std::string::npos || colon + 1 == text.size()) {
    error = "'" + text + "': expected PERSONALITY:DEVICE[:BAUD]";
    return std::nullopt;
  }
  std::string rest = text.substr(colon + 1);
  // A trailing ":digits" is the baud rate; device paths rarely hold a colon.
  const std::size_t last = rest.rfind(':');
  if (last != std::string::npos && last + 1 < rest.size() &&
      rest.find_first_not_of("0123456789", last + 1) == std::string::npos) {
    const std::string digits = rest.substr(last + 1);
    spec.baud = digits.size() <= 7 ? std::atoi(digits.c_str()) : -1;
    rest.resize(last);
    if (!termios_speed(spec.baud)) {
      error = "'" + text + "': unsupported baud rate " + digits +
              " (1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200, 230400)";
      return std::nullopt;
    }
  }
  if (rest.empty()) {
    error = "'" + text + "': the device path is empty";
    return std::nullopt;
  }
  spec.path = rest;
  return spec;
}

std::unique_ptr<protocol::Session> SerialTransport::new_session() const {
  std::unique_ptr<protocol::Session> session = make_session_();
  session->set_peer(access::Peer::line());
  return session;
}

SerialTransport::SerialTransport(asio::io_context& io, std::string name, SerialSpec spec,
                                 int default_baud, SessionFactory make_session)
    : io_(io),
      name_(std::move(name)),
      spec_(std::move(spec)),
      baud_(spec_.baud > 0 ? spec_.baud : default_baud),
      make_session_(std::move(make_session)),
      session_(new_session()),
      line_(io),
      retry_timer_(io) {}

SerialTransport::~SerialTransport() {
  *alive_ = false;
  std::error_code ignored;
  retry_timer_.cancel();
  close_line();
  if (pty_slave_fd_ >= 0) ::close(pty_slave_fd_);
  if (!link_.empty()) {
    // Remove the link only if it is still ours (another rotord may own it now).
    char target[256] = {};
    const ssize_t n = ::readlink(link_.c_str(), target, sizeof(target) - 1);
    if (n > 0 && path_ == std::string(target, static_cast<std::size_t>(n))) ::unlink(link_.c_str());
  }
}

bool SerialTransport::open(std::string& error) {
  return spec_.pty ? open_pty(error) : open_device(error);
}

bool SerialTransport::open_pty(std::string& error) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0) {
    error = "posix_openpt: " + errno_text();
    return false;
  }
  char slave_name[128] = {};
  if (::grantpt(master) != 0 || ::unlockpt(master) != 0 ||
      ::ptsname_r(master, slave_name, sizeof(slave_name)) != 0) {
    error = "pty setup: " + errno_text();
    ::close(master);
    return false;
  }
  path_ = slave_name;
  pty_slave_fd_ = ::open(slave_name, O_RDWR | O_NOCTTY);
  if (pty_slave_fd_ < 0 || !make_raw(pty_slave_fd_, termios_speed(baud_), error)) {
    if (error.empty()) error = std::string("open ") + slave_name + ": " + errno_text();
    ::close(master);
    return false;
  }
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  line_.assign(master);
  if (!spec_.path.empty()) {
    struct stat st {};
    if (::lstat(spec_.path.c_str(), &st) == 0) {
      if (!S_ISLNK(st.st_mode)) {
        error = spec_.path + " exists and is not a symlink; not replacing it";
        return false;
      }
      ::unlink(spec_.path.c_str());
    }
    if (::symlink(path_.c_str(), spec_.path.c_str()) != 0) {
      error = "symlink " + spec_.path + ": " + errno_text();
      return false;
    }
    link_ = spec_.path;
  }
  read();
  return true;
}

bool SerialTransport::open_device(std::string& error) {
  path_ = spec_.path;
  const int fd = ::open(path_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) {
    error = "open " + path_ + ": " + errno_text();
    return false;
  }
  if (!make_raw(fd, termios_speed(baud_), error)) {
    ::close(fd);
    return false;
  }
  ::tcflush(fd, TCIOFLUSH);  // nothing stale from before rotord opened it
  line_.assign(fd);
  reported_failure_ = false;
  read();
  return true;
}

void SerialTransport::read() {
  line_.async_read_some(asio::buffer(buffer_),
                        [this, alive = alive_](std::error_code ec, std::size_t n) {
                          if (!*alive || ec == asio::error::operation_aborted) return;
                          if (ec) return on_line_error(ec);
                          session_->receive(std::string_view(buffer_.data(), n), *this);
                          protocol::drain_output(*session_, *this);
                          // A session that ends itself (rotctld `q`) starts
                          // afresh: the line stays, the next client gets a new one.
                          if (session_->wants_close()) session_ = new_session();
                          read();
                        });
}

void SerialTransport::on_line_error(const std::error_code& ec) {
  if (!reported_failure_) {
    log::warn("%s on %s: %s; retrying every %lld ms", name_.c_str(), path_.c_str(),
              ec.message().c_str(), static_cast<long long>(kReopenInterval.count()));
    reported_failure_ = true;
  }
  // A pty keeps its master (only a read failed); a device is reopened, so an
  // unplugged USB adapter comes back when it is plugged in again.
  if (!spec_.pty) close_line();
  schedule_reopen();
}

void SerialTransport::schedule_reopen() {
  retry_timer_.expires_after(kReopenInterval);
  retry_timer_.async_wait([this, alive = alive_](std::error_code ec) {
    if (!*alive || ec) return;
    if (spec_.pty) return read();
    std::string error;
    if (!open_device(error)) return schedule_reopen();
    log::info("%s on %s again", name_.c_str(), path_.c_str());
  });
}

void SerialTransport::close_line() {
  std::error_code ignored;
  line_.cancel(ignored);
  line_.close(ignored);
}

void SerialTransport::write(std::string_view bytes) {
  if (metrics_ != nullptr) metrics_->on_reply(protocol_, bytes);
  if (!line_.is_open()) {
    dropped_bytes_ += bytes.size();
    return;
  }
  const int fd = line_.native_handle();
  bool flushed = false;
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n > 0) {
      bytes.remove_prefix(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN && spec_.pty && !flushed && pty_slave_fd_ >= 0) {
      // The pty's input queue is full of replies no client read (it closed
      // before reading them): discard those, so the next client gets fresh ones.
      ::tcflush(pty_slave_fd_, TCIFLUSH);
      flushed = true;
      continue;
    }
    dropped_bytes_ += bytes.size();
    return;
  }
}

void SerialTransport::set_session_factory(SessionFactory make_session) {
  make_session_ = std::move(make_session);
  session_ = new_session();
}

void SerialTransport::poll(Millis now) {
  if (!line_.is_open()) return;
  session_->poll(now, *this);
  protocol::drain_output(*session_, *this);
  if (session_->wants_close()) session_ = new_session();
}

}  // namespace rotord::linux_port
