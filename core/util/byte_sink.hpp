#pragma once
#include <cstddef>
#include <string_view>

namespace rotord {

/// Where a session writes its replies. A transport sends each write() as one
/// unit (one TCP segment where it can): Gpredict reads a reply with a single
/// recv and breaks when a reply is split.
///
/// In util, not protocol/, so that the writers below the protocols (the JSON
/// codec, the Prometheus writer) can stream into one.
class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual void write(std::string_view bytes) = 0;
  /// How many bytes write() takes right now without dropping anything: a
  /// transport with a bounded buffer (the Pico's lwIP connection) says so, and
  /// a long reply written through a protocol::WindowSink stops there.
  // Inline on purpose: with no key function, ByteSink's typeinfo is emitted
  // wherever needed, and the ports (built with RTTI) derive from it while
  // the core is built without.
  virtual std::size_t room() const { return static_cast<std::size_t>(-1); }
};

namespace protocol {
/// The name the sessions, transports and writers use (it was declared in
/// protocol/session.hpp until the layers were split).
using rotord::ByteSink;
}  // namespace protocol

}  // namespace rotord
