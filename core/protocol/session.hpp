#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/peer.hpp"
#include "net/line_access.hpp"
#include "rotator/goto_stream.hpp"
#include "util/byte_sink.hpp"
#include "util/time.hpp"

namespace rotord {

class Controller;

namespace protocol {

/// A protocol as a byte session: consumes bytes, appends replies, owns no
/// socket. The same object is unit-tested, fuzzed and served on every port
/// (asio socket, lwIP pcb, pty, USB CDC).
class Session {
 public:
  virtual ~Session() = default;
  /// Bytes arrived from the client; may hold partial or several commands.
  virtual void receive(std::string_view bytes, ByteSink& out) = 0;
  /// Called regularly by the transport for unsolicited output (WRC MONITOR).
  virtual void poll(Millis /*now*/, ByteSink& /*out*/) {}
  /// The client asked to end the session (rotctld `q`); the transport closes
  /// after flushing.
  virtual bool wants_close() const { return false; }
  /// The session only pushes from now on (an HTTP event stream): transports
  /// count it apart from the clients that send requests (net/admission.hpp).
  virtual bool is_event_stream() const { return false; }
  /// HTTP keep-alive: a request was answered and the next has not begun
  /// (net::ClientInfo::between_requests).
  virtual bool between_requests() const { return false; }
  /// A reply longer than a transport may take in one write (the console's
  /// listings) is still going out. A transport with a bounded buffer (the
  /// Pico's USB ports) then feeds no more input and calls write_more() with
  /// the room it has until this is false; one without (Linux) calls
  /// drain_output() after every receive() and poll().
  virtual bool output_pending() const { return false; }
  /// Writes at most `room_bytes` more of the pending reply.
  virtual void write_more(std::size_t /*room_bytes*/, ByteSink& /*out*/) {}

  /// Who the client is; the transport calls this once, before the first byte.
  void set_peer(const access::Peer& peer) { peer_ = peer; }
  const access::Peer& peer() const { return peer_; }
  /// This session as the source of its go-tos: each session is its own
  /// stream for the continuity rule (rotator/goto_stream.hpp).
  CommandSource source() const { return source_of(this); }

 protected:
  /// Whether this client may change anything: its network is allowed
  /// (access::may_control) and nobody holds the control lock (a line client
  /// never can: the lock is taken through the web or REST). Line protocols
  /// refuse every other command but STOP in their own way when not.
  bool may_control(Controller& controller) const;

 private:
  access::Peer peer_;
};

/// Sends all of a session's pending reply at once: for transports that
/// queue whatever is written (Linux's TCP, pty and serial lines).
void drain_output(Session& session, ByteSink& out);

}  // namespace protocol
}  // namespace rotord
