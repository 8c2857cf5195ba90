#pragma once
#include <asio.hpp>
#include <memory>
#include <optional>
#include <string>

#include "protocol/session.hpp"
#include "tcp_server.hpp"

namespace rotord::linux_port {

/// Where one protocol personality is served besides TCP (docs/serial.md).
struct SerialSpec {
  std::string personality;  ///< ServiceConfig::key, e.g. "easycomm"
  bool pty = false;         ///< a pseudo-terminal rotord creates, or a real device
  std::string path;         ///< the device; for a pty an optional symlink to create
  int baud = 0;             ///< devices only; 0 = the personality's default
};

/// Parses `--pty PERSONALITY[:LINK]` or `--serial PERSONALITY:DEVICE[:BAUD]`.
/// Empty with a message in `error` when malformed.
std::optional<SerialSpec> parse_serial_spec(const std::string& text, bool pty, std::string& error);

/// The termios speed constant of a baud rate, if it is one this port offers.
std::optional<unsigned> termios_speed(int baud);

/// Serves one byte session on a pseudo-terminal or a serial device, in the
/// asio loop that runs everything else. A serial line has one client at a
/// time and no "connection": the session lives as long as the line.
///
/// A pty keeps its slave side open in rotord as well, so a client closing
/// it (rotctl exits) never hangs the master up: the next program to open
/// the path simply talks to the same session. A device that fails (a USB
/// adapter unplugged) is closed and reopened every kReopenInterval.
/// Writes never block the loop: bytes a stalled line cannot take are dropped,
/// as a UART with nobody listening would lose them.
class SerialTransport final : private protocol::ByteSink {
 public:
  static constexpr std::size_t kReadChunkBytes = 1024;
  static constexpr std::chrono::milliseconds kReopenInterval{1000};

  SerialTransport(asio::io_context& io, std::string name, SerialSpec spec, int default_baud,
                  SessionFactory make_session);
  ~SerialTransport() override;
  SerialTransport(const SerialTransport&) = delete;
  SerialTransport& operator=(const SerialTransport&) = delete;

  /// Creates the pty (and its link) or opens the device; false with a
  /// message in `error`.
  bool open(std::string& error);
  /// The path clients open: the pty slave (/dev/pts/N) or the device.
  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }
  const SerialSpec& spec() const { return spec_; }
  int baud() const { return baud_; }
  /// Replaces the session (the controller was re-created); the line stays open.
  void set_session_factory(SessionFactory make_session);
  /// Gives the session its chance to send unsolicited output.
  void poll(Millis now);
  std::size_t dropped_bytes() const { return dropped_bytes_; }
  /// Counts the session's error replies under `protocol` (GET /metrics).
  void count_replies(metrics::Registry* registry, metrics::Protocol protocol) {
    metrics_ = registry;
    protocol_ = protocol;
  }

 private:
  void write(std::string_view bytes) override;
  bool open_pty(std::string& error);
  bool open_device(std::string& error);
  void read();
  void on_line_error(const std::error_code& ec);
  void schedule_reopen();
  void close_line();
  /// A session from the factory, told it is on a line (access.serial_control).
  std::unique_ptr<protocol::Session> new_session() const;

  asio::io_context& io_;
  std::string name_;
  SerialSpec spec_;
  int baud_ = 0;
  SessionFactory make_session_;
  std::unique_ptr<protocol::Session> session_;
  asio::posix::stream_descriptor line_;  ///< pty master or device
  int pty_slave_fd_ = -1;                ///< held open so client closes never hang up
  std::string path_;
  std::string link_;  ///< symlink rotord created (removed again on exit)
  asio::steady_timer retry_timer_;
  std::array<char, kReadChunkBytes> buffer_{};
  std::size_t dropped_bytes_ = 0;
  metrics::Registry* metrics_ = nullptr;
  metrics::Protocol protocol_ = metrics::line_metric(protocol::Personality::kWrc);
  bool reported_failure_ = false;
  /// Guards handlers that run after destruction began (the loop outlives us).
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace rotord::linux_port
