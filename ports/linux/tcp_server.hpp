#pragma once
#include <asio.hpp>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <string>

#include "metrics/registry.hpp"
#include "net/admission.hpp"
#include "protocol/session.hpp"
#include "settings/settings.hpp"

namespace rotord::linux_port {

using SessionFactory = std::function<std::unique_ptr<protocol::Session>()>;

struct ServiceConfig {
  std::string name;             ///< for logs, e.g. "WRC text protocol"
  std::uint16_t port = 0;       ///< 0 = disabled
  std::size_t max_clients = 8;  ///< request/line clients; see net/admission.hpp for one more
  std::string reject_message;   ///< sent to a refused client before the close
  SessionFactory make_session;
  /// Short name for --pty / --serial (docs/serial.md), e.g. "easycomm";
  /// empty: TCP only. A service with port 0 can still be served on a pty.
  std::string key{};
  int serial_baud = 9600;  ///< default baud rate of --serial for this protocol
  /// HTTP: event streams served apart from max_clients (web.max_event_streams).
  std::size_t max_event_streams = 0;
  /// net.idle_evict_s, net.max_per_address, access.control_networks, read at
  /// each newcomer; null: a full port refuses, as before issue 12.
  const settings::Settings* settings = nullptr;
  /// Where connections, refusals and error replies are counted (GET
  /// /metrics), under `protocol`; nullptr counts nothing.
  metrics::Registry* metrics = nullptr;
  metrics::Protocol protocol = metrics::line_metric(protocol::Personality::kWrc);
  /// The session of a stop-only exchange (net::Admission's kStopOnly) when
  /// the protocol has a smaller one (HTTP: web::HttpStopOnlySession, as on
  /// the Pico W); empty: make_session's, told set_stop_only().
  SessionFactory make_stop_only_session{};
};

/// Serves one protocol on one TCP port: a byte session per connection, all in
/// the single asio thread that also runs the control tick, so sessions call
/// the controller without locks. Replies go out in the order and units the
/// session wrote them; a client that stops reading is dropped once its
/// backlog passes kMaxBacklogBytes, so it can never block the others.
/// Who gets a slot when the port is full is net::Admission's rule, the same
/// as on the Pico W: a long-idle client makes room, one host never takes
/// every slot, event streams count apart.
class TcpServer {
 public:
  static constexpr std::size_t kMaxBacklogBytes = 256 * 1024;
  static constexpr std::size_t kReadChunkBytes = 4096;
  /// Stop-only exchanges at once (net/admission.hpp), per client slot.
  static constexpr std::size_t kStopOnlyPerClient = 4;

  TcpServer(asio::io_context& io, const asio::ip::address& bind, ServiceConfig config);
  ~TcpServer();
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;

  std::uint16_t port() const { return port_; }
  const std::string& name() const { return config_.name; }
  /// Gives every session its chance to send unsolicited output.
  void poll(Millis now);
  std::size_t client_count() const { return connections_.size(); }
  /// Refusals, evictions and drops since the start (for /metrics).
  const net::ConnectionCounters& counters() const { return admission_.counters(); }

 private:
  class Connection;
  class Snapshot;
  void accept();
  void admit(asio::ip::tcp::socket socket);
  /// `connection` has just become an event stream: keeps the streams within
  /// their limit by closing the oldest.
  void stream_started(Connection* connection);
  void remove(Connection* connection);

  asio::io_context& io_;
  asio::ip::tcp::acceptor acceptor_;
  ServiceConfig config_;
  std::uint16_t port_ = 0;
  std::list<std::shared_ptr<Connection>> connections_;
  net::Admission admission_;
  Millis now_ = 0;  ///< the last poll's: stamps accepts and received bytes
};

}  // namespace rotord::linux_port
