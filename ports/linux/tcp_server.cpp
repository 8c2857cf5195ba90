#include "tcp_server.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "log.hpp"
#include "peer_address.hpp"

namespace rotord::linux_port {
namespace {

/// The client's address, for the access rules (access.control_networks). An
/// IPv4 client of an IPv6 socket (::ffff:a.b.c.d) is an IPv4 client.
access::Peer peer_of(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const asio::ip::address address = socket.remote_endpoint(ec).address();
  if (ec) return {access::Peer::Kind::kOther, 0, {}};
  return linux_port::peer_of(address);
}

/// The client's address, for the per-address cap.
net::Address address_of(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const asio::ip::address address = socket.remote_endpoint(ec).address();
  if (ec) return {};
  if (address.is_v4()) return net::Address::from_ipv4(address.to_v4().to_uint());
  net::Address a;
  const auto bytes = address.to_v6().to_bytes();
  std::copy(bytes.begin(), bytes.end(), a.bytes.begin());
  return a;
}

/// "192.0.2.7:50214" for the logs.
std::string describe(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const asio::ip::tcp::endpoint peer = socket.remote_endpoint(ec);
  if (ec) return "a client";
  const asio::ip::address address = unmapped(peer.address());
  return (address.is_v6() ? "[" + address.to_string() + "]" : address.to_string()) + ":" +
         std::to_string(peer.port());
}

}  // namespace

class TcpServer::Connection final : public protocol::ByteSink,
                                    public std::enable_shared_from_this<Connection> {
 public:
  Connection(TcpServer& server, asio::ip::tcp::socket socket, const net::ClientInfo& info)
      : server_(server), socket_(std::move(socket)), info_(info) {
    std::error_code ignored;
    socket_.set_option(asio::ip::tcp::no_delay(true), ignored);
    // A stop-only exchange is counted as refused (or not at all when it was
    // STOP), not as a client: /metrics' connection counts stay the slots'.
    if (metrics::Registry* m = server_.config_.metrics; m != nullptr && !info_.stop_only)
      m->protocol(server_.config_.protocol).on_accept();
    if (log::enabled(log::Level::kDebug)) {
      client_ = describe(socket_);
      log::debug("%s: %s connected", server_.name().c_str(), client_.c_str());
    }
  }

  void start(std::unique_ptr<protocol::Session> session) {
    session_ = std::move(session);
    session_->set_peer(info_.peer);
    if (info_.stop_only) session_->set_stop_only();
    read();
  }

  const net::ClientInfo& info() {
    info_.between_requests = session_ != nullptr && session_->between_requests();
    return info_;
  }
  void count_as_event_stream() { info_.event_stream = true; }

  void write(std::string_view bytes) override {
    if (closing_) return;
    if (metrics::Registry* m = server_.config_.metrics)
      m->on_reply(server_.config_.protocol, bytes);
    if (pending_.size() + bytes.size() > kMaxBacklogBytes) {
      // The client stopped reading; drop it rather than buffer forever.
      ++server_.admission_.counters().dropped_backlog;
      close();
      return;
    }
    pending_.append(bytes);
    if (!in_session_) flush();
  }

  void poll(Millis now) {
    if (closing_) return;
    if (info_.stop_only && !close_requested_ && now - info_.opened_ms >= net::kStopOnlyExchangeMs) {
      // The stop-only exchange's command never came.
      refuse_and_close();
      return;
    }
    in_session_ = true;
    session_->poll(now, *this);
    protocol::drain_output(*session_, *this);
    in_session_ = false;
    flush();
    // A session may end itself from poll too (HTTP idle and request timeouts).
    if (session_->wants_close()) close_after_flush();
  }

  void close() {
    if (closing_) return;
    closing_ = true;
    if (metrics::Registry* m = server_.config_.metrics; m != nullptr && !info_.stop_only)
      m->protocol(server_.config_.protocol).on_close();
    if (!client_.empty())
      log::debug("%s: %s disconnected", server_.name().c_str(), client_.c_str());
    std::error_code ignored;
    socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
    // Pending handlers hold a shared_ptr, so the object outlives them.
    server_.remove(this);
  }

 private:
  void read() {
    socket_.async_read_some(asio::buffer(buffer_),
                            [this, self = shared_from_this()](std::error_code ec, std::size_t n) {
                              if (ec) {
                                if (ec != asio::error::operation_aborted) close_after_flush();
                                return;
                              }
                              info_.last_receive_ms = server_.now_;
                              in_session_ = true;
                              session_->receive(std::string_view(buffer_.data(), n), *this);
                              protocol::drain_output(*session_, *this);
                              in_session_ = false;
                              flush();
                              if (session_->commands() != commands_seen_) {
                                commands_seen_ = session_->commands();
                                info_.last_useful_ms = server_.now_;
                              }
                              if (session_->exchange_over()) {
                                if (session_->exchange_refused()) {
                                  refuse_and_close();
                                } else {
                                  close_after_flush();
                                }
                                return;
                              }
                              if (!stream_seen_ && session_->is_event_stream()) {
                                stream_seen_ = true;
                                server_.stream_started(this);
                              }
                              if (session_->wants_close()) {
                                close_after_flush();
                                return;
                              }
                              if (!closing_) read();
                            });
  }

  void close_after_flush() {
    close_requested_ = true;
    if (!writing_) close();
  }

  /// A stop-only exchange that was not STOP: the port's busy refusal, as a
  /// client refused outright gets, then the close.
  void refuse_and_close() {
    if (metrics::Registry* m = server_.config_.metrics)
      m->protocol(server_.config_.protocol).on_refuse();
    // Not a reply of the protocol's (no error count), as for a refusal outright.
    if (!closing_) {
      pending_.append(server_.config_.reject_message);
      flush();
    }
    close_after_flush();
  }

  void flush() {
    if (writing_ || pending_.empty() || closing_) return;
    writing_ = true;
    in_flight_.swap(pending_);
    pending_.clear();
    asio::async_write(socket_, asio::buffer(in_flight_),
                      [this, self = shared_from_this()](std::error_code ec, std::size_t) {
                        writing_ = false;
                        in_flight_.clear();
                        if (ec) {
                          close();
                          return;
                        }
                        if (close_requested_ && pending_.empty()) {
                          close();
                          return;
                        }
                        flush();
                      });
  }

  TcpServer& server_;
  asio::ip::tcp::socket socket_;
  net::ClientInfo info_;
  std::unique_ptr<protocol::Session> session_;
  std::array<char, kReadChunkBytes> buffer_{};
  std::string pending_;
  std::string in_flight_;
  bool writing_ = false;
  bool closing_ = false;
  bool close_requested_ = false;
  bool stream_seen_ = false;         ///< the session has become an event stream
  std::uint32_t commands_seen_ = 0;  ///< session_->commands() at the last receive
  /// Inside a session's receive or poll: its writes (a reply is often several,
  /// rotctld's `p` two lines) are gathered and sent once it returns, as one
  /// segment, instead of the first going out alone and the rest waiting a
  /// turn of the event loop for its completion (the 1-client latency tail
  /// the protocol benchmark showed).
  bool in_session_ = false;
  std::string client_;  ///< "address:port", for debug logs only
};

/// The open connections as the admission rule reads them (a copy of the
/// list: accepting is not the tick, so the heap is fine here).
class TcpServer::Snapshot final : public net::ClientList {
 public:
  explicit Snapshot(const std::list<std::shared_ptr<Connection>>& connections) {
    for (const auto& c : connections) entries_.push_back(c.get());
  }
  std::size_t size() const override { return entries_.size(); }
  const net::ClientInfo* at(std::size_t i) const override { return &entries_[i]->info(); }
  Connection* connection(std::size_t i) const { return entries_[i]; }

 private:
  std::vector<Connection*> entries_;
};

TcpServer::TcpServer(asio::io_context& io, const asio::ip::address& bind, ServiceConfig config)
    : io_(io),
      acceptor_(io),
      config_(std::move(config)),
      // Stop-only exchanges, one per host, each 2 s at most: room for more
      // hosts than the port has slots (docs/security.md says what more
      // hosts than that can still do).
      admission_({config_.max_clients, SIZE_MAX, config_.max_event_streams,
                  config_.settings != nullptr ? kStopOnlyPerClient * config_.max_clients : 0},
                 config_.settings) {
  const asio::ip::tcp::endpoint endpoint(bind, config_.port);
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true));
  // "::" serves IPv4 too (as ::ffff:a.b.c.d), whatever net.ipv6.bindv6only says.
  if (bind.is_v6()) acceptor_.set_option(asio::ip::v6_only(false));
  acceptor_.bind(endpoint);
  acceptor_.listen();
  port_ = acceptor_.local_endpoint().port();
  accept();
}

TcpServer::~TcpServer() {
  std::error_code ignored;
  acceptor_.close(ignored);
  // Close every connection, so their pending handlers see a closed connection
  // and never call back into this server (the daemon destroys servers while
  // the loop keeps running when it restarts the controller).
  const std::vector<std::shared_ptr<Connection>> snapshot(connections_.begin(), connections_.end());
  for (const auto& c : snapshot) c->close();
  connections_.clear();
}

void TcpServer::accept() {
  acceptor_.async_accept([this](std::error_code ec, asio::ip::tcp::socket socket) {
    if (ec == asio::error::operation_aborted) return;
    if (!ec) admit(std::move(socket));
    accept();
  });
}

void TcpServer::admit(asio::ip::tcp::socket socket) {
  net::ClientInfo info;
  info.peer = peer_of(socket);
  info.address = address_of(socket);
  info.opened_ms = info.last_receive_ms = info.last_useful_ms = now_;
  const Snapshot snapshot(connections_);
  const net::Admission::Decision d = admission_.admit(snapshot, info, now_);
  info.stop_only = d.kind == net::Admission::Decision::Kind::kStopOnly;
  if (d.kind != net::Admission::Decision::Kind::kAdmit) {
    // Once a minute per host, the rest summed up (log.hpp): a storm of
    // connections cannot flood the log.
    char address[access::kAddressTextBytes];
    const char* why = info.stop_only ? "may only say STOP: no connection free for it"
                      : d.kind == net::Admission::Decision::Kind::kRefusePerAddress
                          ? "refused: its host holds net.max_per_address connections"
                          : "refused: every connection is in use";
    log::from(info.peer, log::Level::kInfo, "%s: %s %s", config_.name.c_str(),
              access::peer_text(info.peer, address), why);
  }
  if (d.kind != net::Admission::Decision::Kind::kAdmit && !info.stop_only) {
    if (config_.metrics != nullptr) config_.metrics->protocol(config_.protocol).on_refuse();
    std::error_code ignored;
    asio::write(socket, asio::buffer(config_.reject_message), ignored);
    socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
    return;
  }
  // The one making room goes without a word: none of the protocols has a
  // message for it, and a client that was really idle will just reconnect.
  if (d.evict != net::Admission::kNone) {
    if (config_.metrics != nullptr) config_.metrics->protocol(config_.protocol).on_evict();
    snapshot.connection(d.evict)->close();
  }
  connections_.push_back(std::make_shared<Connection>(*this, std::move(socket), info));
  connections_.back()->start(info.stop_only && config_.make_stop_only_session
                                 ? config_.make_stop_only_session()
                                 : config_.make_session());
}

void TcpServer::stream_started(Connection* connection) {
  // Without a stream limit a stream stays an ordinary client.
  if (admission_.limits().max_event_streams == 0) return;
  connection->count_as_event_stream();
  const Snapshot snapshot(connections_);
  std::size_t self = net::Admission::kNone;
  for (std::size_t i = 0; i < snapshot.size(); ++i) {
    if (snapshot.connection(i) == connection) self = i;
  }
  const std::size_t victim = admission_.stream_started(snapshot, self);
  if (victim == net::Admission::kNone) return;
  if (config_.metrics != nullptr) config_.metrics->protocol(config_.protocol).on_evict();
  snapshot.connection(victim)->close();
}

void TcpServer::remove(Connection* connection) {
  connections_.remove_if([connection](const auto& c) { return c.get() == connection; });
}

void TcpServer::poll(Millis now) {
  now_ = now;
  // A poll may close its connection (backlog full), which edits the list.
  const std::vector<std::shared_ptr<Connection>> snapshot(connections_.begin(), connections_.end());
  for (const auto& c : snapshot) c->poll(now);
}

}  // namespace rotord::linux_port
