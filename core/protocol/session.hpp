#pragma once
#include <string_view>

#include "access/peer.hpp"
#include "net/line_access.hpp"
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

  /// Who the client is; the transport calls this once, before the first byte.
  void set_peer(const access::Peer& peer) { peer_ = peer; }
  const access::Peer& peer() const { return peer_; }

 protected:
  /// Whether this client may change anything: its network is allowed
  /// (access::may_control) and nobody holds the control lock (a line client
  /// never can: the lock is taken through the web or REST). Line protocols
  /// refuse every other command but STOP in their own way when not.
  bool may_control(Controller& controller) const;

 private:
  access::Peer peer_;
};

}  // namespace protocol
}  // namespace rotord
