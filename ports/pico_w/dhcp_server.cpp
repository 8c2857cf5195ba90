#include "dhcp_server.hpp"

#include <algorithm>
#include <cstring>

#include "lwip/ip4_addr.h"
#include "lwip/ip_addr.h"
#include "lwip/netif.h"
#include "lwip/pbuf.h"
#include "lwip/udp.h"

namespace rotord::lwip_port {

namespace {

// RFC 2131 / 2132 layout and codes.
constexpr std::size_t kOp = 0, kHtype = 1, kHlen = 2, kXid = 4, kFlags = 10, kCiaddr = 12,
                      kYiaddr = 16, kSiaddr = 20, kChaddr = 28, kCookie = 236, kOptions = 240;
constexpr std::uint8_t kBootRequest = 1, kBootReply = 2;
constexpr std::uint32_t kMagicCookie = 0x63825363;
constexpr std::uint8_t kOptPad = 0, kOptMask = 1, kOptRouter = 3, kOptRequestedIp = 50,
                       kOptLeaseTime = 51, kOptMessageType = 53, kOptServerId = 54, kOptEnd = 255;
constexpr std::uint8_t kDiscover = 1, kOffer = 2, kRequest = 3, kAck = 5, kNak = 6;
constexpr std::uint16_t kServerPort = 67, kClientPort = 68;

std::uint32_t get_be32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
         (static_cast<std::uint32_t>(p[2]) << 8) | p[3];
}

void put_be32(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 24);
  p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8);
  p[3] = static_cast<std::uint8_t>(v);
}

/// Finds option `code` in the options area; its value and length, or null.
const std::uint8_t* find_option(const std::uint8_t* opts, std::size_t size, std::uint8_t code,
                                std::size_t& length) {
  std::size_t i = 0;
  while (i < size) {
    const std::uint8_t c = opts[i];
    if (c == kOptEnd) break;
    if (c == kOptPad) {
      ++i;
      continue;
    }
    if (i + 1 >= size) break;
    const std::size_t len = opts[i + 1];
    if (i + 2 + len > size) break;  // truncated option: ignore the rest
    if (c == code) {
      length = len;
      return opts + i + 2;
    }
    i += 2 + len;
  }
  return nullptr;
}

}  // namespace

struct DhcpServer::Glue {
  static void on_recv(void* arg, udp_pcb* /*pcb*/, pbuf* p, const ip_addr_t* /*addr*/,
                      u16_t /*port*/) {
    auto* server = static_cast<DhcpServer*>(arg);
    if (p == nullptr) return;
    const std::size_t n = pbuf_copy_partial(
        p, server->in_.data(), static_cast<u16_t>(std::min<std::size_t>(p->tot_len, 548)), 0);
    pbuf_free(p);
    server->handle(n);
  }
};

DhcpServer::~DhcpServer() {
  stop();
}

bool DhcpServer::start(netif* itf) {
  stop();
  udp_pcb* pcb = udp_new();
  if (pcb == nullptr) return false;
  if (udp_bind(pcb, IP_ANY_TYPE, kServerPort) != ERR_OK) {
    udp_remove(pcb);
    return false;
  }
  // Replies go to the broadcast address: the client has no address yet.
  ip_set_option(pcb, SOF_BROADCAST);
  udp_recv(pcb, &Glue::on_recv, this);
  pcb_ = pcb;
  netif_ = itf;
  return true;
}

void DhcpServer::stop() {
  if (pcb_ == nullptr) return;
  udp_remove(pcb_);
  pcb_ = nullptr;
  netif_ = nullptr;
}

void DhcpServer::handle(std::size_t length) {
  if (netif_ == nullptr || length < kOptions || in_[kOp] != kBootRequest || in_[kHtype] != 1 ||
      in_[kHlen] != 6 || get_be32(&in_[kCookie]) != kMagicCookie)
    return;
  const std::uint8_t* opts = &in_[kOptions];
  const std::size_t opts_size = length - kOptions;
  std::size_t len = 0;
  const std::uint8_t* type = find_option(opts, opts_size, kOptMessageType, len);
  if (type == nullptr || len != 1) return;

  const std::uint32_t server_ip = lwip_ntohl(ip4_addr_get_u32(netif_ip4_addr(netif_)));
  const std::size_t lease = lease_for(&in_[kChaddr]);
  const std::uint32_t lease_ip =
      (server_ip & 0xFFFFFF00u) | static_cast<std::uint32_t>(kFirstHost + lease);

  if (*type == kDiscover) {
    reply(kOffer, lease_ip);
    return;
  }
  if (*type != kRequest) return;  // DECLINE, RELEASE, INFORM: nothing to do
  // A REQUEST for another server's offer is not ours to answer.
  const std::uint8_t* server_id = find_option(opts, opts_size, kOptServerId, len);
  if (server_id != nullptr && (len != 4 || get_be32(server_id) != server_ip)) return;
  const std::uint8_t* requested = find_option(opts, opts_size, kOptRequestedIp, len);
  const std::uint32_t wanted =
      requested != nullptr && len == 4 ? get_be32(requested) : get_be32(&in_[kCiaddr]);
  reply(wanted == lease_ip ? kAck : kNak, wanted == lease_ip ? lease_ip : 0);
}

std::size_t DhcpServer::lease_for(const std::uint8_t* mac) {
  for (std::size_t i = 0; i < leases_.size(); ++i) {
    if (leases_[i].used && std::memcmp(leases_[i].mac.data(), mac, 6) == 0) return i;
  }
  std::size_t i = 0;
  while (i < leases_.size() && leases_[i].used) ++i;
  if (i == leases_.size()) {  // full: reuse the oldest allocation
    i = next_reuse_;
    next_reuse_ = (next_reuse_ + 1) % leases_.size();
  }
  leases_[i].used = true;
  std::memcpy(leases_[i].mac.data(), mac, 6);
  return i;
}

void DhcpServer::reply(std::uint8_t type, std::uint32_t your_ip) {
  const std::uint32_t server_ip = lwip_ntohl(ip4_addr_get_u32(netif_ip4_addr(netif_)));
  const std::uint32_t mask = lwip_ntohl(ip4_addr_get_u32(netif_ip4_netmask(netif_)));
  out_.fill(0);
  out_[kOp] = kBootReply;
  out_[kHtype] = 1;
  out_[kHlen] = 6;
  std::memcpy(&out_[kXid], &in_[kXid], 4);
  std::memcpy(&out_[kFlags], &in_[kFlags], 2);
  put_be32(&out_[kYiaddr], your_ip);
  put_be32(&out_[kSiaddr], type == kNak ? 0 : server_ip);
  std::memcpy(&out_[kChaddr], &in_[kChaddr], 16);
  put_be32(&out_[kCookie], kMagicCookie);
  std::uint8_t* o = &out_[kOptions];
  *o++ = kOptMessageType;
  *o++ = 1;
  *o++ = type;
  *o++ = kOptServerId;
  *o++ = 4;
  put_be32(o, server_ip);
  o += 4;
  if (type != kNak) {
    *o++ = kOptLeaseTime;
    *o++ = 4;
    put_be32(o, kLeaseSeconds);
    o += 4;
    *o++ = kOptMask;
    *o++ = 4;
    put_be32(o, mask);
    o += 4;
    *o++ = kOptRouter;  // phones want a gateway before they use the network
    *o++ = 4;
    put_be32(o, server_ip);
    o += 4;
  }
  *o++ = kOptEnd;
  // BOOTP's minimum message is 300 bytes; some clients drop shorter ones.
  const std::size_t size = std::max<std::size_t>(static_cast<std::size_t>(o - out_.data()), 300);

  pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(size), PBUF_RAM);
  if (p == nullptr) return;  // out of memory: the client retries
  pbuf_take(p, out_.data(), static_cast<u16_t>(size));
  udp_sendto_if(pcb_, p, IP_ADDR_BROADCAST, kClientPort, netif_);
  pbuf_free(p);
}

}  // namespace rotord::lwip_port
