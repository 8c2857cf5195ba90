#include "lwip_transport.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "lwip/err.h"
#include "lwip/ip_addr.h"
#include "lwip/pbuf.h"
#include "lwip/tcp.h"

namespace rotord::lwip_port {

// The header spells err_t as std::int8_t so it needs no lwIP include.
static_assert(std::is_same_v<err_t, std::int8_t>, "lwIP's err_t is expected to be s8_t");

namespace {

/// Unregisters every callback of a connection pcb, so lwIP never calls into a
/// slot that was released (the pico-examples close path does the same).
void detach(tcp_pcb* pcb) {
  tcp_arg(pcb, nullptr);
  tcp_recv(pcb, nullptr);
  tcp_sent(pcb, nullptr);
  tcp_err(pcb, nullptr);
  tcp_poll(pcb, nullptr, 0);
}

/// The client's address, for the access rules (access.control_networks).
access::Peer peer_of(const tcp_pcb* pcb) {
#if LWIP_IPV4
  if (IP_IS_V4_VAL(pcb->remote_ip))
    return access::Peer::from_ipv4(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(&pcb->remote_ip))));
#endif
#if LWIP_IPV6
  // Not in the image (lwipopts.h: no LWIP_IPV6, docs/pico_w.md), but ready.
  if (IP_IS_V6_VAL(pcb->remote_ip)) {
    access::IpBytes bytes{};
    std::memcpy(bytes.data(), ip_2_ip6(&pcb->remote_ip)->addr, bytes.size());  // network order
    return access::Peer::from_ipv6(bytes);
  }
#endif
  return {access::Peer::Kind::kOther, 0, {}};
}

/// The client's address, for the per-address cap.
net::Address address_of(const tcp_pcb* pcb) {
#if LWIP_IPV4
  if (IP_IS_V4_VAL(pcb->remote_ip))
    return net::Address::from_ipv4(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(&pcb->remote_ip))));
#endif
#if LWIP_IPV6
  if (IP_IS_V6_VAL(pcb->remote_ip)) {
    std::uint8_t bytes[16];
    std::memcpy(bytes, ip_2_ip6(&pcb->remote_ip)->addr, sizeof(bytes));  // network order
    return net::Address::from_ipv6(bytes);
  }
#endif
  return {};
}

}  // namespace

/// The slots as the admission rule reads them; a free slot is null.
class TcpServer::SlotList final : public net::ClientList {
 public:
  /// `shared`: the shared stop-only slot's connection while this server
  /// holds it (its last entry), else null.
  SlotList(std::span<Connection> slots, const Connection* shared)
      : slots_(slots), shared_(shared) {}
  std::size_t size() const override { return slots_.size() + 1; }
  const net::ClientInfo* at(std::size_t i) const override {
    if (i == slots_.size()) return shared_ != nullptr ? &shared_->info_ : nullptr;
    return slots_[i].active() ? &slots_[i].info_ : nullptr;
  }

 private:
  std::span<Connection> slots_;
  const Connection* shared_;
};

struct TcpServer::Glue {
  static err_t on_accept(void* arg, tcp_pcb* pcb, err_t err) {
    auto* server = static_cast<TcpServer*>(arg);
    if (err != ERR_OK || pcb == nullptr || server == nullptr) return ERR_VAL;
    net::ClientInfo info;
    info.peer = peer_of(pcb);
    info.address = address_of(pcb);
    info.opened_ms = info.last_receive_ms = info.last_useful_ms = server->now_;
    // Whether each client waits between two HTTP requests, as of now: such a
    // keep-alive connection makes room at once (net/admission.hpp), as on Linux.
    for (Connection& s : server->slots_) {
      if (s.active()) s.info_.between_requests = s.session_->between_requests();
    }
    const net::Admission::Decision d = server->admission_.admit(
        SlotList(server->slots_, server->shared_held()), info, server->now_);
    info.stop_only = d.kind == net::Admission::Decision::Kind::kStopOnly;
    if (d.kind != net::Admission::Decision::Kind::kAdmit && !info.stop_only)
      return reject(*server, pcb);
    // The one making room gets a FIN, no message (no protocol has one). What
    // close() returns concerns that pcb, not this callback's.
    if (d.evict != net::Admission::kNone) server->close(server->slots_[d.evict]);
    protocol::Session* session = nullptr;
    Connection* c = server->open_slot(info.stop_only, session);
    if (session == nullptr) {
      if (info.stop_only) {
        // The shared stop-only slot is another port's now: refused after all.
        --server->admission_.counters().stop_only;
        ++server->admission_.counters().refused_full;
      }
      return reject(*server, pcb);
    }

    ++server->stats_.accepted;
    // A stop-only exchange is counted as refused (or not at all), not as a client.
    if (metrics::Registry* m = server->config_.metrics; m != nullptr && !info.stop_only)
      m->protocol(server->config_.protocol).on_accept();
    c->server_ = server;
    c->pcb_ = pcb;
    c->session_ = session;
    c->info_ = info;
    c->commands_seen_ = 0;
    session->set_peer(info.peer);
    if (info.stop_only) session->set_stop_only();
    c->reset_output();
    // Replies are small and clients (Gpredict) wait for each one: no Nagle
    // delay, like TCP_NODELAY on Linux.
    tcp_nagle_disable(pcb);
    tcp_arg(pcb, c);
    tcp_recv(pcb, &Glue::on_recv);
    tcp_sent(pcb, &Glue::on_sent);
    tcp_err(pcb, &Glue::on_err);
    tcp_poll(pcb, &Glue::on_poll, kLwipPollInterval);
    return ERR_OK;
  }

  /// Refuses a client over the limit with the protocol's message, as the
  /// Linux port does, so the user sees why instead of a bare reset.
  static err_t reject(TcpServer& server, tcp_pcb* pcb) {
    ++server.stats_.rejected;
    if (metrics::Registry* m = server.config_.metrics)
      m->protocol(server.config_.protocol).on_refuse();
    detach(pcb);
    const std::string_view msg = server.config_.reject_message;
    if (!msg.empty() && msg.size() <= tcp_sndbuf(pcb)) {
      if (tcp_write(pcb, msg.data(), static_cast<u16_t>(msg.size()), TCP_WRITE_FLAG_COPY) == ERR_OK)
        tcp_output(pcb);
    }
    // Data queued by tcp_write is still sent before the FIN.
    if (tcp_close(pcb) != ERR_OK) {
      tcp_abort(pcb);
      return ERR_ABRT;
    }
    return ERR_OK;
  }

  static err_t on_recv(void* arg, tcp_pcb* pcb, pbuf* p, err_t err) {
    auto* c = static_cast<Connection*>(arg);
    if (p == nullptr) {  // the peer closed its side
      if (c == nullptr) return ERR_OK;
      return c->server_->close(*c);
    }
    if (c == nullptr || err != ERR_OK) {
      // Not ours any more (or lwIP reports an error with data): consume it so
      // the window reopens and the pbuf is not leaked.
      tcp_recved(pcb, p->tot_len);
      pbuf_free(p);
      return ERR_OK;
    }
    c->info_.last_receive_ms = c->server_->now_;
    for (const pbuf* q = p; q != nullptr && !c->overflow_; q = q->next) {
      c->session_->receive(std::string_view(static_cast<const char*>(q->payload), q->len), *c);
    }
    tcp_recved(pcb, p->tot_len);
    pbuf_free(p);
    c->server_->after_input(*c);
    if (!c->stream_seen_ && c->session_->is_event_stream()) {
      c->stream_seen_ = true;
      c->server_->stream_started(*c);
    }
    if (c->session_->wants_close()) c->close_requested_ = true;
    return c->server_->settle(*c);
  }

  static err_t on_sent(void* arg, tcp_pcb* /*pcb*/, u16_t /*len*/) {
    auto* c = static_cast<Connection*>(arg);
    if (c == nullptr) return ERR_OK;
    c->flush();
    c->continue_reply();
    return c->server_->settle(*c);
  }

  static err_t on_poll(void* arg, tcp_pcb* /*pcb*/) {
    auto* c = static_cast<Connection*>(arg);
    if (c == nullptr) return ERR_OK;
    c->flush();
    c->continue_reply();
    return c->server_->settle(*c);
  }

  /// lwIP has already freed the pcb (reset, out of memory, timeout): only the
  /// slot is left to release; the pcb must not be touched.
  static void on_err(void* arg, err_t /*err*/) {
    auto* c = static_cast<Connection*>(arg);
    if (c == nullptr || c->server_ == nullptr) return;
    ++c->server_->stats_.closed;
    c->pcb_ = nullptr;
    c->server_->release(*c);
  }
};

void TcpServer::Connection::write(std::string_view bytes) {
  if (pcb_ == nullptr || overflow_ || bytes.empty()) return;
  if (metrics::Registry* m = server_->config_.metrics)
    m->on_reply(server_->config_.protocol, bytes);
  write_uncounted(bytes);
}

void TcpServer::Connection::write_uncounted(std::string_view bytes) {
  if (pcb_ == nullptr || overflow_ || bytes.empty()) return;
  const auto immutable = server_->config_.is_immutable;
  if (bytes.size() >= kMinReferenceBytes && immutable != nullptr &&
      immutable(bytes.data(), bytes.size())) {
    if (!push_chunk(bytes.data(), bytes.size())) return;
  } else {
    // Nothing queued: straight into lwIP's send buffer, so the shared
    // stop-only slot's small buffer takes an HTTP head too. Never more than
    // a full buffer's worth at once, on any connection: a larger copied
    // write drops the client, as it always has.
    if (chunk_count_ == 0 && bytes.size() <= kOutputBytes) bytes.remove_prefix(write_direct(bytes));
    if (bytes.empty() || overflow_) return;
    if (bytes.size() > out_.size() - out_len_ || !push_chunk(nullptr, bytes.size())) {
      // The client stopped reading: drop it rather than block or buffer more.
      // The drop itself happens after the session call returns (settle()),
      // because lwIP forbids freeing the pcb under a callback that continues.
      overflow_ = true;
      return;
    }
    std::memcpy(out_.data() + out_len_, bytes.data(), bytes.size());
    out_len_ += bytes.size();
  }
  flush();
}

std::size_t TcpServer::Connection::write_direct(std::string_view bytes) {
  const std::size_t n =
      std::min({bytes.size(), std::size_t{tcp_sndbuf(pcb_)}, std::size_t{0xFFFF}});
  if (n == 0) return 0;
  const err_t err = tcp_write(pcb_, bytes.data(), static_cast<u16_t>(n), TCP_WRITE_FLAG_COPY);
  if (err == ERR_MEM) return 0;  // lwIP's pbufs exhausted: buffered, flushed on sent/poll
  if (err != ERR_OK) {
    overflow_ = true;  // the connection is unusable (e.g. not connected any more)
    return 0;
  }
  tcp_output(pcb_);
  return n;
}

std::size_t TcpServer::Connection::room() const {
  if (pcb_ == nullptr || overflow_) return 0;
  // Copied bytes join the last piece when it is copied too; else they need a
  // queue entry of their own.
  const bool joins_last = chunk_count_ > 0 && chunks_[chunk_count_ - 1].data == nullptr;
  if (!joins_last && chunk_count_ == chunks_.size()) return 0;
  return out_.size() - out_len_;
}

void TcpServer::Connection::continue_reply() {
  if (pcb_ == nullptr || overflow_ || session_ == nullptr || !session_->output_pending()) return;
  if (room() < kMinWindowBytes) return;  // the peer acknowledges more first
  session_->write_more(static_cast<std::size_t>(-1), *this);
  if (session_->wants_close()) close_requested_ = true;
}

bool TcpServer::Connection::push_chunk(const char* data, std::size_t size) {
  if (chunk_count_ > 0) {
    Chunk& last = chunks_[chunk_count_ - 1];
    if (data == nullptr && last.data == nullptr) {  // copied bytes are contiguous in out_
      last.size += size;
      return true;
    }
  }
  if (chunk_count_ == chunks_.size()) {
    overflow_ = true;
    return false;
  }
  chunks_[chunk_count_++] = Chunk{data, size};
  return true;
}

void TcpServer::Connection::flush() {
  if (pcb_ == nullptr || overflow_) return;
  bool queued = false;
  while (chunk_count_ > 0) {
    Chunk& chunk = chunks_[0];
    const std::size_t room = tcp_sndbuf(pcb_);
    if (room == 0) break;  // tcp_sent will call again when the peer acknowledges
    const std::size_t n = std::min({chunk.size, room, std::size_t{0xFFFF}});
    const bool copied = chunk.data == nullptr;
    // Copied bytes are copied again into lwIP (our buffer is reused at once);
    // immutable ones are referenced until the peer acknowledges them.
    const err_t err = tcp_write(pcb_, copied ? out_.data() : chunk.data, static_cast<u16_t>(n),
                                copied ? TCP_WRITE_FLAG_COPY : 0);
    if (err == ERR_MEM) break;  // segment queue or pbufs exhausted: retry on sent/poll
    if (err != ERR_OK) {
      overflow_ = true;  // the connection is unusable (e.g. not connected any more)
      return;
    }
    queued = true;
    if (copied) {
      out_len_ -= n;
      std::memmove(out_.data(), out_.data() + n, out_len_);
    } else {
      chunk.data += n;
    }
    chunk.size -= n;
    if (chunk.size == 0) {
      std::copy(chunks_.begin() + 1, chunks_.begin() + static_cast<std::ptrdiff_t>(chunk_count_),
                chunks_.begin());
      --chunk_count_;
    }
  }
  if (queued) tcp_output(pcb_);
}

void TcpServer::Connection::reset_output() {
  out_len_ = 0;
  chunk_count_ = 0;
  overflow_ = false;
  close_requested_ = false;
}

TcpServer::TcpServer(ServerConfig config, SessionPool& sessions, std::span<Connection> slots,
                     std::span<char> output)
    : config_(config),
      sessions_(sessions),
      slots_(slots),
      admission_({std::min(config.max_clients, slots.size() - config.stop_only_slots),
                  slots.size() - config.stop_only_slots, config.max_event_streams,
                  config.settings != nullptr
                      ? config.stop_only_slots + (config.shared_stop_only != nullptr ? 1 : 0)
                      : 0},
                 config.settings) {
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    slots_[i].server_ = this;
    slots_[i].index_ = i;
    slots_[i].out_ = output.subspan(i * kOutputBytes, kOutputBytes);
  }
}

TcpServer::~TcpServer() {
  stop();
}

bool TcpServer::start() {
  if (listener_ != nullptr) return true;
  tcp_pcb* pcb = tcp_new_ip_type(IPADDR_TYPE_ANY);
  if (pcb == nullptr) return false;
  if (tcp_bind(pcb, IP_ANY_TYPE, config_.port) != ERR_OK) {
    tcp_close(pcb);  // never connected: tcp_close just frees it
    return false;
  }
  const u16_t bound_port = pcb->local_port;
  // On success tcp_listen frees `pcb` and returns a smaller listen pcb.
  tcp_pcb* listener = tcp_listen_with_backlog(pcb, TCP_DEFAULT_LISTEN_BACKLOG);
  if (listener == nullptr) {
    tcp_close(pcb);
    return false;
  }
  listener_ = listener;
  port_ = bound_port;
  tcp_arg(listener_, this);
  tcp_accept(listener_, &Glue::on_accept);
  return true;
}

void TcpServer::stop() {
  for (Connection& c : slots_) {
    if (c.pcb_ != nullptr) close(c);
  }
  if (Connection* shared = shared_held()) close(*shared);
  if (listener_ != nullptr) {
    tcp_arg(listener_, nullptr);
    tcp_accept(listener_, nullptr);
    tcp_close(listener_);  // never fails for a listen pcb
    listener_ = nullptr;
  }
}

void TcpServer::poll(Millis now) {
  now_ = now;
  for (Connection& c : slots_) poll(c, now);
  if (Connection* shared = shared_held()) poll(*shared, now);
}

void TcpServer::poll(Connection& c, Millis now) {
  if (c.pcb_ == nullptr) return;
  if (c.info_.stop_only && !c.close_requested_ &&
      now - c.info_.opened_ms >= net::kStopOnlyExchangeMs)
    end_exchange(c, true);  // its command never came
  c.session_->poll(now, c);
  c.flush();
  c.continue_reply();
  settle(c);  // outside any lwIP callback: the returned ERR_ABRT is nobody's
}

std::size_t TcpServer::client_count() const {
  return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(),
                                                [](const Connection& c) { return c.active(); })) +
         (shared_held() != nullptr ? 1 : 0);
}

TcpServer::Connection* TcpServer::shared_held() const {
  SharedStopOnly* shared = config_.shared_stop_only;
  if (shared == nullptr || shared->connection_.server_ != this || !shared->connection_.active())
    return nullptr;
  return &shared->connection_;
}

TcpServer::Connection* TcpServer::open_slot(bool stop_only, protocol::Session*& session) {
  session = nullptr;
  SharedStopOnly* shared = config_.shared_stop_only;
  if (stop_only && config_.stop_only_slots == 0) {
    // Admission counted the shared slot as this server's; another server's
    // exchange may hold it: then this newcomer is refused as before.
    if (shared == nullptr || shared->connection_.active()) return nullptr;
    session = sessions_.open_at(shared->storage_, shared->bytes_);
    if (session == nullptr) return nullptr;
    shared->connection_.server_ = this;
    shared->connection_.index_ = slots_.size();  // past the server's own
    return &shared->connection_;
  }
  Connection* c = free_slot();
  if (c != nullptr) session = sessions_.open(c->index_);
  return c;
}

TcpServer::Connection* TcpServer::free_slot() {
  // The admission rule has kept the count within the limits already.
  for (Connection& c : slots_) {
    if (!c.active()) return &c;
  }
  return nullptr;
}

void TcpServer::stream_started(Connection& c) {
  // Without a stream limit a stream stays an ordinary client.
  if (admission_.limits().max_event_streams == 0) return;
  c.info_.event_stream = true;
  const std::size_t victim = admission_.stream_started(SlotList(slots_, shared_held()), c.index_);
  if (victim != net::Admission::kNone) close(slots_[victim]);
}

void TcpServer::after_input(Connection& c) {
  if (c.session_ == nullptr) return;
  if (c.session_->commands() != c.commands_seen_) {
    c.commands_seen_ = c.session_->commands();
    c.info_.last_useful_ms = now_;
  }
  if (c.session_->exchange_over() && !c.close_requested_)
    end_exchange(c, c.session_->exchange_refused());
}

void TcpServer::end_exchange(Connection& c, bool refused) {
  if (refused) {
    if (metrics::Registry* m = config_.metrics) m->protocol(config_.protocol).on_refuse();
    c.write_uncounted(config_.reject_message);  // not a reply of the protocol's
  }
  c.close_requested_ = true;  // settle() closes once the reply is out
}

err_t TcpServer::settle(Connection& c) {
  if (c.pcb_ == nullptr) return ERR_OK;
  if (c.overflow_) {
    ++stats_.dropped_backlog;
    ++admission_.counters().dropped_backlog;
    return drop(c);
  }
  if (c.close_requested_ && c.idle()) return close(c);
  return ERR_OK;
}

err_t TcpServer::close(Connection& c) {
  tcp_pcb* pcb = c.pcb_;
  if (pcb == nullptr) return ERR_OK;
  ++stats_.closed;
  detach(pcb);
  release(c);
  if (tcp_close(pcb) != ERR_OK) {
    // Out of memory for the FIN: lwIP's rule is to abort and report ERR_ABRT
    // so the calling callback does not touch the pcb again.
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  return ERR_OK;
}

err_t TcpServer::drop(Connection& c) {
  tcp_pcb* pcb = c.pcb_;
  if (pcb == nullptr) return ERR_OK;
  detach(pcb);  // tcp_abort calls the err callback; the slot is released here
  release(c);
  tcp_abort(pcb);
  return ERR_ABRT;
}

void TcpServer::release(Connection& c) {
  if (c.session_ != nullptr) {
    if (&c == shared_held()) {
      c.session_->~Session();  // in the shared slot's storage
    } else {
      sessions_.release(c.index_);
    }
    if (config_.metrics != nullptr && !c.info_.stop_only)
      config_.metrics->protocol(config_.protocol).on_close();
  }
  c.session_ = nullptr;
  c.pcb_ = nullptr;
  c.info_ = {};
  c.stream_seen_ = false;
  c.reset_output();
}

}  // namespace rotord::lwip_port
