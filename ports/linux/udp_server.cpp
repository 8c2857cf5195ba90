#include "udp_server.hpp"

#include "log.hpp"
#include "peer_address.hpp"

namespace rotord::linux_port {

UdpServer::UdpServer(asio::io_context& io, const asio::ip::address& bind, std::uint16_t port,
                     std::string name, protocol::DatagramProtocol& protocol,
                     protocol::DatagramPersonality personality, metrics::Registry* metrics)
    : socket_(io),
      name_(std::move(name)),
      protocol_(protocol),
      personality_(personality),
      metrics_(metrics) {
  const asio::ip::udp::endpoint endpoint(bind, port);
  socket_.open(endpoint.protocol());
  // Another program on this host may listen for the same broadcasts.
  socket_.set_option(asio::socket_base::reuse_address(true));
  // "::" hears IPv4 senders too (as ::ffff:a.b.c.d).
  if (bind.is_v6()) socket_.set_option(asio::ip::v6_only(false));
  socket_.bind(endpoint);
  port_ = socket_.local_endpoint().port();
  receive();
}

void UdpServer::receive() {
  socket_.async_receive_from(asio::buffer(buffer_), from_,
                             [this](std::error_code ec, std::size_t size) {
                               if (ec == asio::error::operation_aborted) return;
                               if (!ec) handle(size);
                               receive();
                             });
}

void UdpServer::handle(std::size_t size) {
  const asio::ip::address address = from_.address();
  const access::Peer peer = peer_of(address);
  protocol::DatagramReplies replies;
  // A datagram that filled the buffer was longer than the protocol reads
  // (the kernel dropped the rest): the handler refuses it by its size.
  const protocol::DatagramOutcome outcome =
      protocol_.receive(std::string_view(buffer_.data(), size), peer, replies);
  if (metrics_ != nullptr) metrics_->on_datagram(personality_, outcome);
  if (outcome != protocol::DatagramOutcome::kDone)
    log::debug("%s: datagram from %s %s", name_.c_str(), unmapped(address).to_string().c_str(),
               protocol::outcome_name(outcome));
  send(replies, address);
}

void UdpServer::poll() {
  protocol::DatagramReplies replies;
  access::Peer to;
  if (!protocol_.poll(replies, to) || !to.is_network()) return;
  std::error_code ec;
  const bool v6_socket = socket_.local_endpoint(ec).address().is_v6();
  send(replies, address_of(to, v6_socket));
}

void UdpServer::send(const protocol::DatagramReplies& replies, const asio::ip::address& to) {
  for (std::size_t i = 0; i < replies.count(); ++i) {
    const protocol::DatagramReplies::Reply& reply = replies[i];
    std::error_code ignored;  // a reply that cannot go out is lost, as UDP may lose it
    socket_.send_to(asio::buffer(reply.bytes.data(), reply.size),
                    asio::ip::udp::endpoint(to, reply.port), 0, ignored);
  }
}

}  // namespace rotord::linux_port
