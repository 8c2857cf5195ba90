#pragma once
// The Pico W's TCP transport for core byte sessions, on lwIP's raw API.
//
// Portable lwIP code with no pico-sdk include: the firmware builds it against
// the SDK's lwIP (NO_SYS=1, pico_cyw43_arch_lwip_poll) and tests/lwip builds
// the same file against Debian's liblwip-dev, so the network glue that only
// runs on the Pico is exercised in CI.
//
// Threading: lwIP calls back into this code and the port calls poll() and the
// control tick; all of it must run in one context (the Pico's poll loop, or
// with the lwIP core lock held on a NO_SYS=0 host), so sessions call the
// controller without locks.
#include <array>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>

#include "metrics/registry.hpp"
#include "net/admission.hpp"
#include "protocol/session.hpp"

struct tcp_pcb;

namespace rotord::lwip_port {

/// Makes and destroys the sessions of one server in caller-owned storage, so a
/// connection never allocates (no heap after start-up).
class SessionPool {
 public:
  virtual ~SessionPool() = default;
  virtual std::size_t capacity() const = 0;
  /// Constructs the session of slot `slot`; null when the slot is taken.
  virtual protocol::Session* open(std::size_t slot) = 0;
  virtual void release(std::size_t slot) = 0;
  /// Constructs a session in storage outside the pool (the shared stop-only
  /// slot); null when it does not fit. Destroyed by its virtual destructor.
  virtual protocol::Session* open_at(void* storage, std::size_t bytes) = 0;
};

/// N sessions of type S built in place by `make()` (which returns an S by
/// value; guaranteed copy elision means S need not be movable). The session
/// of a stop-only exchange in the shared slot is `make_stop_only()`'s, by
/// default the same; HTTP's is a much smaller one (web::HttpStopOnlySession).
template <typename S, std::size_t N, typename Make, typename MakeStopOnly = Make>
class StaticSessionPool final : public SessionPool {
 public:
  explicit StaticSessionPool(Make make) requires std::is_same_v<Make, MakeStopOnly>
      : make_(make), make_stop_only_(std::move(make)) {}
  StaticSessionPool(Make make, MakeStopOnly make_stop_only)
      : make_(std::move(make)), make_stop_only_(std::move(make_stop_only)) {}
  ~StaticSessionPool() override {
    for (std::size_t i = 0; i < N; ++i) release(i);
  }
  StaticSessionPool(const StaticSessionPool&) = delete;
  StaticSessionPool& operator=(const StaticSessionPool&) = delete;

  std::size_t capacity() const override { return N; }
  protocol::Session* open(std::size_t slot) override {
    if (slot >= N || live_[slot] != nullptr) return nullptr;
    live_[slot] = ::new (static_cast<void*>(storage_[slot].bytes)) S(make_());
    return live_[slot];
  }
  void release(std::size_t slot) override {
    if (slot >= N || live_[slot] == nullptr) return;
    live_[slot]->~S();
    live_[slot] = nullptr;
  }
  protocol::Session* open_at(void* storage, std::size_t bytes) override {
    using T = decltype(std::declval<MakeStopOnly&>()());
    if (bytes < sizeof(T) || reinterpret_cast<std::uintptr_t>(storage) % alignof(T) != 0)
      return nullptr;
    return ::new (storage) T(make_stop_only_());
  }

 private:
  struct alignas(S) Slot {
    unsigned char bytes[sizeof(S)];
  };
  Make make_;
  MakeStopOnly make_stop_only_;
  std::array<Slot, N> storage_{};
  std::array<S*, N> live_{};
};

class SharedStopOnly;

struct ServerConfig {
  const char* name = "";            ///< for logs, e.g. "WRC text protocol"
  std::uint16_t port = 0;           ///< 0 = an ephemeral port (tests)
  std::size_t max_clients = 4;      ///< clamped to the slots given; see net/admission.hpp
  std::string_view reject_message;  ///< sent to a refused client before the close
  /// True when [data, data + size) stays unchanged for the life of the
  /// program (the Pico's flash: the web UI's gzipped files). Such writes are
  /// queued by reference and handed to lwIP without a copy, so a 20 KB page
  /// needs neither a 20 KB buffer nor a copy. nullptr: everything is copied.
  bool (*is_immutable)(const void* data, std::size_t size) = nullptr;
  /// net.idle_evict_s, net.max_per_address, access.control_networks, read at
  /// each newcomer; null: a full port refuses, as before issue 12.
  const settings::Settings* settings = nullptr;
  /// HTTP: event streams apart from max_clients. They share the static slots,
  /// so a newcomer finding every slot taken drops the oldest stream first.
  std::size_t max_event_streams = 0;
  /// Of the slots given, how many are kept for stop-only exchanges (a
  /// newcomer to a full port may still say STOP: net/admission.hpp).
  /// StaticService sets it.
  std::size_t stop_only_slots = 0;
  /// One stop-only slot shared with other servers (the Pico W's line ports,
  /// which have no RAM for one each): used when the server has none of its
  /// own, by one exchange at a time across them all. nullptr: none.
  SharedStopOnly* shared_stop_only = nullptr;
  /// Where connections, refusals and error replies are counted (GET
  /// /metrics), under `protocol`; nullptr counts nothing.
  metrics::Registry* metrics = nullptr;
  metrics::Protocol protocol = metrics::line_metric(protocol::Personality::kWrc);
};

/// Serves one protocol on one TCP port: a byte session per connection from a
/// static pool. Mirrors ports/linux/tcp_server: replies go out in the order
/// and units the session wrote them (Nagle off), and a client that stops
/// reading is dropped once its copied backlog passes the per-connection
/// output buffer, so it can never exhaust memory or block the others. Who
/// gets a slot is net::Admission's rule, as on Linux: a long-idle client
/// makes room, one host never takes every slot, event streams count apart.
class TcpServer {
  struct Glue;  // the lwIP callbacks (lwip_transport.cpp)

 public:
  /// Per-connection output buffer: what the session wrote and lwIP's send
  /// buffer could not take yet. A WRC reply is < 128 bytes and MONITOR pushes
  /// ~60 bytes every 100 ms, so 1 KiB is seconds of a stalled client.
  static constexpr std::size_t kOutputBytes = 1024;
  /// Pending output as a queue of pieces: copied bytes (in the buffer above)
  /// and immutable bytes passed by reference, in the order they were written.
  static constexpr std::size_t kMaxChunks = 8;
  /// Immutable writes shorter than this are copied anyway: a reference costs
  /// a queue entry and an lwIP pbuf, which only pays off for large bodies.
  static constexpr std::size_t kMinReferenceBytes = 256;
  /// lwIP's coarse poll (units of 500 ms): retries a flush that ran out of
  /// lwIP memory and a close that failed.
  static constexpr std::uint8_t kLwipPollInterval = 2;
  /// A long reply's next window is written only with at least this much
  /// room: each window writes the reply again from its start.
  static constexpr std::size_t kMinWindowBytes = kOutputBytes / 2;

  /// One connection slot; the storage is the caller's (a static array).
  class Connection final : public protocol::ByteSink {
   public:
    void write(std::string_view bytes) override;
    /// What write() takes now without dropping the client: the output
    /// buffer's free bytes (lwIP's send buffer drains it on every write).
    std::size_t room() const override;
    bool active() const { return pcb_ != nullptr; }

   private:
    friend class TcpServer;
    friend class SharedStopOnly;
    friend struct Glue;
    struct Chunk {
      const char* data = nullptr;  ///< nullptr: the next bytes of out_
      std::size_t size = 0;
    };
    /// write() without counting it as the protocol's reply (/metrics).
    void write_uncounted(std::string_view bytes);
    /// With nothing queued: as much of `bytes` (at most kOutputBytes) as
    /// lwIP's send buffer takes, copied straight there, so a reply larger
    /// than out_ (an HTTP head in the shared stop-only slot) needs no room
    /// of ours. Returns how many bytes went.
    std::size_t write_direct(std::string_view bytes);
    bool push_chunk(const char* data, std::size_t size);
    void flush();
    /// A session with a reply longer than lwIP's send buffer (the HTTP
    /// session's long GET responses): its next window, once there is room
    /// for a useful one. Called when the peer acknowledges data (tcp_sent),
    /// on lwIP's poll and on the server's.
    void continue_reply();
    bool idle() const { return chunk_count_ == 0; }
    void reset_output();

    TcpServer* server_ = nullptr;
    tcp_pcb* pcb_ = nullptr;
    protocol::Session* session_ = nullptr;
    net::ClientInfo info_;
    bool stream_seen_ = false;         ///< the session has become an event stream
    std::uint32_t commands_seen_ = 0;  ///< session_->commands() at the last receive
    std::size_t index_ = 0;
    /// The output buffer: kOutputBytes of the service's storage, or the
    /// shared stop-only slot's few (SharedStopOnly::kOutputBytes).
    std::span<char> out_;
    std::size_t out_len_ = 0;
    std::array<Chunk, kMaxChunks> chunks_{};
    std::size_t chunk_count_ = 0;
    bool overflow_ = false;         ///< backlog full or lwIP refused: drop it
    bool close_requested_ = false;  ///< close once the output is flushed
  };

  struct Stats {
    std::uint32_t accepted = 0;
    std::uint32_t rejected = 0;         ///< refused (full or per address); counters() says which
    std::uint32_t dropped_backlog = 0;  ///< output buffer overflowed
    std::uint32_t closed = 0;           ///< by the peer, the session or an error
  };

  /// `output`: kOutputBytes for each slot, in order (StaticService holds them).
  TcpServer(ServerConfig config, SessionPool& sessions, std::span<Connection> slots,
            std::span<char> output);
  ~TcpServer();
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;

  /// Binds and listens on every address. False when lwIP refuses (port in
  /// use, out of pcbs); the server is then inert.
  bool start();
  /// Closes every connection and the listener.
  void stop();
  /// Gives every session its chance to send unsolicited output (WRC MONITOR)
  /// and retries pending output. Call from the loop that ticks the controller.
  void poll(Millis now);

  std::uint16_t port() const { return port_; }
  const char* name() const { return config_.name; }
  std::size_t client_count() const;
  const Stats& stats() const { return stats_; }
  /// Refusals, evictions and drops by kind (for /metrics), as on Linux.
  const net::ConnectionCounters& counters() const { return admission_.counters(); }

 private:
  class SlotList;
  friend class SharedStopOnly;
  Connection* free_slot();
  /// The shared stop-only slot's connection when this server holds it.
  Connection* shared_held() const;
  /// A connection and its session for a newcomer: a free slot of its own,
  /// or for a stop-only exchange without slots of its own the shared one.
  Connection* open_slot(bool stop_only, protocol::Session*& session);
  /// Entry `c` has just become an event stream: closes the oldest other one
  /// when the streams are over their limit.
  void stream_started(Connection& c);
  /// Called after every session call from an lwIP callback: applies a drop
  /// or a requested close. Returns what the callback must return (ERR_ABRT
  /// once the pcb is gone).
  std::int8_t settle(Connection& c);
  /// After the session took input: stamps a known command as use, and ends
  /// a stop-only exchange whose command came (with the busy refusal when it
  /// was not STOP) or whose time ran out.
  void after_input(Connection& c);
  void end_exchange(Connection& c, bool refused);
  void poll(Connection& c, Millis now);
  std::int8_t close(Connection& c);
  std::int8_t drop(Connection& c);
  void release(Connection& c);

  ServerConfig config_;
  SessionPool& sessions_;
  std::span<Connection> slots_;
  tcp_pcb* listener_ = nullptr;
  std::uint16_t port_ = 0;
  Stats stats_;
  net::Admission admission_;
  Millis now_ = 0;  ///< the last poll's: stamps accepts and received bytes
};

/// One stop-only slot for several servers (ServerConfig::shared_stop_only):
/// a Connection and room for the largest of their sessions, held by one
/// server's exchange at a time. A STOP-only exchange is one short line and
/// lasts net::kStopOnlyExchangeMs at most, so one slot serves newcomers to
/// every full line port in turn; while it is taken, the next is refused as
/// before. The web port shares it too, with its small stop-only session
/// (web::HttpStopOnlySession), whose reply goes straight into lwIP's send
/// buffer (Connection::write_direct), past this small output buffer.
class SharedStopOnly {
 public:
  /// Its output buffer: a STOP-only exchange writes one short reply, or the
  /// port's busy refusal (a session that writes more is dropped).
  static constexpr std::size_t kOutputBytes = 128;

  SharedStopOnly(void* storage, std::size_t bytes) : storage_(storage), bytes_(bytes) {
    connection_.out_ = output_;
  }
  SharedStopOnly(const SharedStopOnly&) = delete;
  SharedStopOnly& operator=(const SharedStopOnly&) = delete;
  const TcpServer* holder() const { return connection_.active() ? connection_.server_ : nullptr; }

 private:
  friend class TcpServer;
  TcpServer::Connection connection_;
  std::array<char, kOutputBytes> output_{};
  void* storage_;
  std::size_t bytes_;
};

/// SharedStopOnly with its session storage: `Bytes` the largest session's size.
template <std::size_t Bytes, std::size_t Align = alignof(std::max_align_t)>
class StaticSharedStopOnly : public SharedStopOnly {
 public:
  /// What a session must fit (static_assert it where the slot is made).
  using Storage = unsigned char[Bytes];
  static constexpr std::size_t kAlign = Align;
  StaticSharedStopOnly() : SharedStopOnly(session_bytes_, Bytes) {}

 private:
  alignas(Align) Storage session_bytes_;
};

/// A server with its own session pool and connection slots, meant for static
/// storage (the firmware's composition root): N for clients and StopOnly more
/// for stop-only exchanges (each a Connection and an S: their RAM is counted
/// in ports/pico_w/README.md).
template <typename S, std::size_t N, typename Make, std::size_t StopOnly = 0,
          typename MakeStopOnly = Make>
class StaticService {
 public:
  StaticService(ServerConfig config, Make make) requires std::is_same_v<Make, MakeStopOnly>
      : pool_(std::move(make)), server_(with_stop_only(config), pool_, slots_, output_) {}
  /// `make_stop_only`: the session of an exchange in the shared stop-only slot.
  StaticService(ServerConfig config, Make make, MakeStopOnly make_stop_only)
      : pool_(std::move(make), std::move(make_stop_only)),
        server_(with_stop_only(config), pool_, slots_, output_) {}
  TcpServer& server() { return server_; }

 private:
  static ServerConfig with_stop_only(ServerConfig config) {
    config.stop_only_slots = StopOnly;
    return config;
  }
  std::array<TcpServer::Connection, N + StopOnly> slots_{};
  std::array<char, (N + StopOnly) * TcpServer::kOutputBytes> output_{};
  StaticSessionPool<S, N + StopOnly, Make, MakeStopOnly> pool_;
  TcpServer server_;  // last: constructed after, destroyed before its storage
};

}  // namespace rotord::lwip_port
