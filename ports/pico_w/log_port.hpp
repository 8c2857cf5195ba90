#pragma once
// The Pico W's USB log port (CDC 0, "rotord log"): where printf goes.
//
// pico_stdio_usb drops output while no terminal holds the port open, so the
// lines a user most needs -- the boot banner, the Wi-Fi state, the addresses
// and ports -- were lost: they are printed in the first second, before anyone
// can open the port. LogPort keeps what nobody has read in a ring and sends it,
// in order, when a terminal opens the port.
//
// Portable code with no pico-sdk or TinyUSB include, like usb_cdc_link.hpp:
// the firmware gives it TinyUSB's CDC interface 0 through a stdio driver
// (main.cpp), tests/usb a fake.
//
// Threading: write() runs inside printf, service() in the firmware's one
// loop after tud_task(); nothing runs in an interrupt.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "usb_cdc_link.hpp"

namespace rotord::usb_port {

/// Log output on one CDC port, never lost for want of a listener and never
/// waiting for one:
///
/// - Someone listens when the host has configured the device and a program
///   holds the port open (DTR high), as pico_stdio_usb decides.
/// - While someone listens and nothing is queued, output goes straight into
///   the CDC FIFO; what the FIFO cannot take waits in the ring.
/// - While nobody listens, output waits in the ring. When a program opens
///   the port, service() sends the ring's contents first, then what follows.
/// - The ring keeps the newest kRingBytes. When it is full the oldest whole
///   lines make room, and the next reader is told how many bytes it missed.
/// - Input on the log port goes to the console (protocol/console_session.hpp)
///   when one is attached, else it is read and dropped. The console's
///   replies join the log output in order; a long listing goes out in
///   windows of the ring's free room, and the input typed meanwhile waits
///   in the CDC FIFO (USB's own flow control).
class LogPort final : private protocol::ByteSink {
 public:
  /// Enough for a boot's log (banner, settings, pins, Wi-Fi, every service's
  /// port: about 1.5 KB) with room for the Wi-Fi retries that follow.
  static constexpr std::size_t kRingBytes = 4096;

  struct Stats {
    std::uint32_t dropped_bytes = 0;  ///< oldest log output the ring gave up
    std::uint32_t unheard_bytes = 0;  ///< write_live() output nobody heard
    std::uint32_t sent_bytes = 0;     ///< handed to the port
  };

  explicit LogPort(CdcPort& port) : port_(port) {}
  LogPort(const LogPort&) = delete;
  LogPort& operator=(const LogPort&) = delete;

  /// Input bytes handed to the console per service(), so a host flooding
  /// the port cannot hold up the loop.
  static constexpr std::size_t kMaxConsoleInputPerService = 512;

  /// Log output: sent now if someone listens, else kept for the next reader.
  void write(std::string_view bytes) override;
  /// Serves `console` on this port (from now on, for good): a session on a
  /// local line, so access.serial_control decides whether it may control.
  void attach_console(protocol::Session& console);
  /// Output that only means something as it happens (WRC MONITOR lines):
  /// dropped while nobody listens, so it never pushes the log out of the ring.
  void write_live(std::string_view bytes);
  /// Sends what waits in the ring while someone listens, drops input. Call on
  /// every loop pass, after tud_task().
  void service();

  /// Bytes waiting in the ring.
  std::size_t backlog_bytes() const { return size_; }
  const Stats& stats() const { return stats_; }

 private:
  bool listening() const { return port_.connected() && port_.dtr(); }
  void serve_console();
  /// Writes to the port as much of `bytes` as the FIFO takes; returns that.
  std::size_t send(std::string_view bytes);
  void keep(std::string_view bytes);
  void drop_oldest(std::size_t bytes);
  /// The oldest bytes of the ring that lie in one piece (up to its wrap).
  std::string_view first_piece() const;

  CdcPort& port_;
  protocol::Session* console_ = nullptr;
  std::array<char, kRingBytes> ring_{};
  std::size_t head_ = 0;  ///< the oldest byte
  std::size_t size_ = 0;
  /// Bytes dropped since the last reader was told.
  std::uint32_t untold_dropped_ = 0;
  Stats stats_;
};

}  // namespace rotord::usb_port
