#include "tcp_server.hpp"

#include <array>
#include <vector>

#include "log.hpp"

namespace rotord::linux_port {
namespace {

/// The client's address, for the access rules (access.control_networks). An
/// IPv4 client of an IPv6 socket (::ffff:a.b.c.d) is an IPv4 client.
access::Peer peer_of(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const asio::ip::address address = socket.remote_endpoint(ec).address();
  if (ec) return {access::Peer::Kind::kOther, 0};
  if (address.is_v4()) return access::Peer::from_ipv4(address.to_v4().to_uint());
  if (address.is_v6() && address.to_v6().is_v4_mapped())
    return access::Peer::from_ipv4(
        asio::ip::make_address_v4(asio::ip::v4_mapped, address.to_v6()).to_uint());
  return {access::Peer::Kind::kOther, 0};
}

/// "192.0.2.7:50214" for the logs.
std::string describe(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const asio::ip::tcp::endpoint peer = socket.remote_endpoint(ec);
  if (ec) return "a client";
  return peer.address().to_string() + ":" + std::to_string(peer.port());
}

}  // namespace

class TcpServer::Connection final : public protocol::ByteSink,
                                    public std::enable_shared_from_this<Connection> {
 public:
  Connection(TcpServer& server, asio::ip::tcp::socket socket,
             std::unique_ptr<protocol::Session> session)
      : server_(server), socket_(std::move(socket)), session_(std::move(session)) {
    std::error_code ignored;
    socket_.set_option(asio::ip::tcp::no_delay(true), ignored);
    session_->set_peer(peer_of(socket_));
    if (metrics::Registry* m = server_.config_.metrics)
      m->protocol(server_.config_.protocol).on_accept();
    if (log::enabled(log::Level::kDebug)) {
      client_ = describe(socket_);
      log::debug("%s: %s connected", server_.name().c_str(), client_.c_str());
    }
  }

  void start() { read(); }

  void write(std::string_view bytes) override {
    if (closing_) return;
    if (metrics::Registry* m = server_.config_.metrics)
      m->on_reply(server_.config_.protocol, bytes);
    if (pending_.size() + bytes.size() > kMaxBacklogBytes) {
      close();  // the client stopped reading; drop it rather than buffer forever
      return;
    }
    pending_.append(bytes);
    flush();
  }

  void poll(Millis now) {
    if (closing_) return;
    session_->poll(now, *this);
    // A session may end itself from poll too (HTTP idle and request timeouts).
    if (session_->wants_close()) close_after_flush();
  }

  void close() {
    if (closing_) return;
    closing_ = true;
    if (metrics::Registry* m = server_.config_.metrics)
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
                              session_->receive(std::string_view(buffer_.data(), n), *this);
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
  std::unique_ptr<protocol::Session> session_;
  std::array<char, kReadChunkBytes> buffer_{};
  std::string pending_;
  std::string in_flight_;
  bool writing_ = false;
  bool closing_ = false;
  bool close_requested_ = false;
  std::string client_;  ///< "address:port", for debug logs only
};

TcpServer::TcpServer(asio::io_context& io, const asio::ip::address& bind, ServiceConfig config)
    : io_(io), acceptor_(io), config_(std::move(config)) {
  const asio::ip::tcp::endpoint endpoint(bind, config_.port);
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true));
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
    if (!ec) {
      if (connections_.size() >= config_.max_clients) {
        if (config_.metrics != nullptr) config_.metrics->protocol(config_.protocol).on_refuse();
        if (log::enabled(log::Level::kDebug))
          log::debug("%s: %s refused, %zu clients already", config_.name.c_str(),
                     describe(socket).c_str(), connections_.size());
        std::error_code ignored;
        asio::write(socket, asio::buffer(config_.reject_message), ignored);
        socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
        socket.close(ignored);
      } else {
        connections_.push_back(
            std::make_shared<Connection>(*this, std::move(socket), config_.make_session()));
        connections_.back()->start();
      }
    }
    accept();
  });
}

void TcpServer::remove(Connection* connection) {
  connections_.remove_if([connection](const auto& c) { return c.get() == connection; });
}

void TcpServer::poll(Millis now) {
  // A poll may close its connection (backlog full), which edits the list.
  const std::vector<std::shared_ptr<Connection>> snapshot(connections_.begin(), connections_.end());
  for (const auto& c : snapshot) c->poll(now);
}

}  // namespace rotord::linux_port
