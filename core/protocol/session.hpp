#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/peer.hpp"
#include "command/command_log.hpp"
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
  /// The protocol's key ("rotctld", "wrc"; its row's in protocol_registry):
  /// the front end named in each command's log line (command/command_log.hpp).
  /// Empty (no line) for a session that is no line protocol (HTTP, whose
  /// commands the REST API logs as "rest").
  virtual std::string_view front() const { return {}; }
  /// This client as the sender of a command, for the command layer.
  command::Origin origin() const { return {front(), peer_}; }

  /// Over capacity (net::Admission's kStopOnly): the connection is one short
  /// exchange in which only STOP is obeyed. The transport says so before the
  /// first byte; it ends the exchange after the first command, or at its
  /// deadline (net::kStopOnlyExchangeMs).
  void set_stop_only() { stop_only_ = true; }
  bool stop_only() const { return stop_only_; }
  /// Stop-only: the command came, the exchange is over; the transport closes
  /// once the reply is out, after the port's busy refusal when it was not
  /// STOP (exchange_refused: the session then neither acted nor replied).
  bool exchange_over() const { return exchange_over_; }
  bool exchange_refused() const { return exchange_refused_; }
  /// Commands (HTTP requests) this client sent that the protocol knows:
  /// what makes a connection "used" for the admission rule
  /// (net::ClientInfo::last_useful_ms). Line ends alone do not count, so a
  /// client that only keeps a connection warm stays idle.
  std::uint32_t commands() const { return commands_; }

 protected:
  /// A recognised command arrived; `is_stop` when it is the protocol's STOP.
  /// False: a stop-only exchange refuses it (the session must do nothing).
  bool command_arrives(bool is_stop) {
    ++commands_;
    if (!stop_only_) return true;
    if (exchange_over_) return false;
    exchange_over_ = true;
    exchange_refused_ = !is_stop;
    return is_stop;
  }

  /// Whether this client may change anything: its network is allowed
  /// (access::may_control) and nobody holds the control lock (a line client
  /// never can: the lock is taken through the web or REST). Line protocols
  /// refuse every other command but STOP in their own way when not. The
  /// rule is the command layer's (command::may_control), for this peer; a
  /// refusal of `what` (the protocol's name of the command) is logged there.
  bool may_control(Controller& controller, std::string_view what) const;

 private:
  access::Peer peer_;
  std::uint32_t commands_ = 0;
  bool stop_only_ = false;
  bool exchange_over_ = false;
  bool exchange_refused_ = false;
};

/// Sends all of a session's pending reply at once: for transports that
/// queue whatever is written (Linux's TCP, pty and serial lines).
void drain_output(Session& session, ByteSink& out);

}  // namespace protocol
}  // namespace rotord
