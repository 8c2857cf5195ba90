#include "lwip_udp.hpp"

#include <algorithm>

#include "lwip/ip_addr.h"
#include "lwip/pbuf.h"
#include "lwip/udp.h"

namespace rotord::lwip_port {

struct UdpService::Glue {
  static void on_recv(void* arg, udp_pcb* /*pcb*/, pbuf* p, const ip_addr_t* addr, u16_t /*port*/) {
    auto* service = static_cast<UdpService*>(arg);
    if (p == nullptr) return;
    // At most one byte more than the protocol reads: enough to know it is
    // too long without copying the rest.
    const std::size_t n = pbuf_copy_partial(
        p, service->in_.data(),
        static_cast<u16_t>(std::min<std::size_t>(p->tot_len, service->in_.size())), 0);
    pbuf_free(p);
    service->handle(n, addr);
  }
};

UdpService::~UdpService() {
  stop();
}

bool UdpService::start(std::uint16_t port) {
  stop();
  udp_pcb* pcb = udp_new();
  if (pcb == nullptr) return false;
  if (udp_bind(pcb, IP_ANY_TYPE, port) != ERR_OK) {
    udp_remove(pcb);
    return false;
  }
  // N1MM+ may broadcast its rotor messages.
  ip_set_option(pcb, SOF_BROADCAST);
  udp_recv(pcb, &Glue::on_recv, this);
  pcb_ = pcb;
  port_ = pcb->local_port;
  return true;
}

void UdpService::stop() {
  if (pcb_ == nullptr) return;
  udp_remove(pcb_);
  pcb_ = nullptr;
}

void UdpService::handle(std::size_t size, const void* from_addr) {
  const auto* addr = static_cast<const ip_addr_t*>(from_addr);
  access::Peer peer{access::Peer::Kind::kOther, 0, {}};
  if (IP_IS_V4(addr)) peer = access::Peer::from_ipv4(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(addr))));
  protocol::DatagramReplies replies;
  last_outcome_ = protocol_.receive(std::string_view(in_.data(), size), peer, replies);
  ++datagrams_;
  if (metrics_ != nullptr) metrics_->on_datagram(personality_, last_outcome_);
  send(replies, addr);
}

void UdpService::poll() {
  protocol::DatagramReplies replies;
  access::Peer to;
  if (pcb_ == nullptr || !protocol_.poll(replies, to) || to.kind != access::Peer::Kind::kIpv4)
    return;
  ip_addr_t addr{};
  IP_SET_TYPE_VAL(addr, IPADDR_TYPE_V4);
  ip4_addr_set_u32(ip_2_ip4(&addr), lwip_htonl(to.ipv4));
  send(replies, &addr);
}

void UdpService::send(const protocol::DatagramReplies& replies, const void* to_addr) {
  const auto* addr = static_cast<const ip_addr_t*>(to_addr);
  for (std::size_t i = 0; i < replies.count(); ++i) {
    const protocol::DatagramReplies::Reply& reply = replies[i];
    pbuf* q = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(reply.size), PBUF_RAM);
    if (q == nullptr) return;  // out of pbufs: the answer is lost, as UDP may lose it
    pbuf_take(q, reply.bytes.data(), static_cast<u16_t>(reply.size));
    udp_sendto(pcb_, q, addr, reply.port);
    pbuf_free(q);
  }
}

}  // namespace rotord::lwip_port
