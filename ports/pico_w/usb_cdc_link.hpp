#pragma once
// A core byte session on a USB CDC ACM serial port: the Pico W's
// counterpart of ports/linux/serial_transport, for PstRotator, N1MM+ or
// Hamlib on a COM port (docs/serial.md, ports/pico_w/README.md "USB").
//
// Portable code with no pico-sdk or TinyUSB include: the firmware gives it
// TinyUSB's CDC interface 1 (usb_cdc_port.hpp) and tests/usb gives it a fake,
// so the line handling that otherwise only runs on the Pico is tested on the
// host.
//
// Threading: service() and poll() run in the firmware's one loop, after
// tud_task(), like every other transport; nothing here runs in an interrupt.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "protocol/session.hpp"

namespace rotord::usb_port {

/// One CDC ACM interface as the link sees it: the hardware boundary.
/// Every call returns at once; none waits for the host.
class CdcPort {
 public:
  virtual ~CdcPort() = default;
  /// The host has configured the device (enumerated and not suspended).
  virtual bool connected() const = 0;
  /// A program holds the port open with DTR raised.
  virtual bool dtr() const = 0;
  /// How often DTR has gone from low to high since boot: a program that
  /// closes and reopens the port between two calls is still seen.
  virtual std::uint32_t opens() const = 0;
  /// Copies up to `max_bytes` received bytes; 0 when none are waiting.
  virtual std::size_t read(char* buffer, std::size_t max_bytes) = 0;
  /// Bytes write() takes right now without dropping anything.
  virtual std::size_t write_available() const = 0;
  /// Queues bytes for the host; returns how many it took.
  virtual std::size_t write(const char* data, std::size_t bytes) = 0;
  /// Starts sending what write() queued (a short reply is otherwise held
  /// until a full USB packet is queued).
  virtual void flush() = 0;
  /// Drops output the host has not read yet.
  virtual void discard_output() = 0;
  /// Drops input the session has not read yet.
  virtual void discard_input() = 0;
};

/// Builds the link's session in storage the caller owns (the firmware has no
/// heap after start-up).
class SessionMaker {
 public:
  virtual ~SessionMaker() = default;
  /// Destroys the current session, if any, and builds a fresh one.
  virtual protocol::Session& renew() = 0;
};

/// Serves one byte session on one CDC port. A serial line has no
/// connection of its own, so the link makes one from the modem lines:
///
/// - A program raising DTR (opening the port) gets a fresh session: no half
///   line of the previous client, no reply it never read.
/// - DTR falling (the program closed the port, or died mid-line) or the
///   host going away (cable pulled, PC asleep) ends the session and drops
///   unread input and output.
/// - Output goes out only while someone listens: DTR is high, or the client
///   has sent bytes since the session began. The second rule serves
///   programs that never raise DTR (.NET's SerialPort leaves it off by
///   default; the pico-sdk has PICO_STDIO_USB_CONNECTION_WITHOUT_DTR for
///   them). With nobody listening, output is dropped, never queued.
/// - Writes never wait. A reply that the CDC FIFO and the link's buffer
///   cannot take whole is dropped whole and counted (Stats), so a client
///   that stops reading sees whole replies or none, never half a line, and
///   the control tick never stalls. Input the session has not read stays in
///   TinyUSB's FIFO, which NAKs the host: USB's own flow control.
class UsbCdcLink final : private protocol::ByteSink {
 public:
  /// Bytes read from the port per read() call: one full-speed USB packet.
  static constexpr std::size_t kReadChunkBytes = 64;
  /// Input handed to the session per service(), so a host flooding the port
  /// cannot hold up the loop; the rest waits in the FIFO for the next pass.
  static constexpr std::size_t kMaxInputBytesPerService = 512;
  /// Output the CDC FIFO could not take yet. The longest reply of any
  /// session (rotctld dump_caps, 1536 bytes) fits whole.
  static constexpr std::size_t kPendingBytes = 2048;

  struct Stats {
    std::uint32_t sessions = 0;         ///< sessions begun (the first included)
    std::uint32_t dropped_replies = 0;  ///< writes dropped: FIFO and buffer full
    std::uint32_t dropped_bytes = 0;    ///< their bytes
    std::uint32_t unheard_bytes = 0;    ///< output dropped: nobody listening
    std::uint32_t received_bytes = 0;
    std::uint32_t sent_bytes = 0;  ///< handed to the port
  };

  /// Begins the first session at once.
  UsbCdcLink(CdcPort& port, SessionMaker& sessions);
  UsbCdcLink(const UsbCdcLink&) = delete;
  UsbCdcLink& operator=(const UsbCdcLink&) = delete;

  /// Follows the modem lines, feeds received bytes to the session and
  /// moves buffered output on. Call on every loop pass, after tud_task().
  void service();
  /// Gives the session its chance to send unsolicited output (WRC MONITOR).
  /// Call at the control tick.
  void poll(Millis now);

  const Stats& stats() const { return stats_; }
  /// Output waiting in the link's buffer for room in the CDC FIFO.
  std::size_t pending_bytes() const { return tail_ - head_; }

 private:
  void write(std::string_view bytes) override;
  bool listening() const { return connected_ && (dtr_ || heard_); }
  void restart(bool drop_input);
  void pump_input();
  /// Lets a session with a long reply pending write as much as the buffer
  /// has room for (protocol::Session::write_more).
  void continue_reply();
  void pump_output();
  bool append_pending(std::string_view bytes);

  CdcPort& port_;
  SessionMaker& sessions_;
  protocol::Session* session_ = nullptr;
  bool connected_ = false;
  bool dtr_ = false;
  bool heard_ = false;  ///< the client sent bytes in this session
  std::uint32_t opens_ = 0;
  std::array<char, kPendingBytes> pending_{};
  std::size_t head_ = 0;  ///< pending output is pending_[head_, tail_)
  std::size_t tail_ = 0;
  Stats stats_;
};

}  // namespace rotord::usb_port
