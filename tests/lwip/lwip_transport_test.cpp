// The Pico W's lwIP transport against Debian's lwIP: real TCP state machines
// on both ends, a server pcb from ports/pico_w/lwip_transport.cpp and client
// pcbs from the raw API, over one netif that loops packets sent to its own
// address back into the stack (LWIP_NETIF_LOOPBACK).
//
// Debian's liblwip is built with NO_SYS=0 and core locking, so lwIP runs its
// own tcpip thread; the test holds the core lock around every lwIP call and
// every server poll, which gives the transport the single context it gets
// from the Pico's poll loop. Waits are bounded by a step count, not a clock.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dhcp_server.hpp"
#include "fake_rotator.hpp"
#include "lwip_transport.hpp"
// Debian's lwipopts.h declares the core-lock functions outside lwIP's own
// extern "C" blocks; without this they would get C++ linkage.
extern "C" {
#include "lwip/init.h"
#include "lwip/ip_addr.h"
#include "lwip/netif.h"
#include "lwip/tcp.h"
#include "lwip/tcpip.h"
#include "lwip/udp.h"
}
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/protocol_registry.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/window_sink.hpp"
#include "protocol/wrc_session.hpp"
#include "settings/settings.hpp"
#include "web/http_session.hpp"
#include "web/http_stop_only_session.hpp"
#include "web/web_api.hpp"

// The options must be Debian's, the ones liblwip.so was built with (struct
// layouts depend on them), not the Pico's ports/pico_w/config/lwipopts.h.
#include "lwip_harness.hpp"

static_assert(NO_SYS == 0 && LWIP_TCPIP_CORE_LOCKING == 1, "not Debian's lwipopts.h");

namespace rotord {
namespace {

using lwip_port::ServerConfig;
using lwip_port::StaticService;
using lwip_port::TcpServer;

using testing::CoreLock;
using testing::ensure_lwip;

/// A raw-API client pcb and what it saw.
struct Client {
  tcp_pcb* pcb = nullptr;
  std::string received;
  bool connected = false;
  bool peer_closed = false;  ///< FIN from the server
  bool reset = false;        ///< the err callback ran (RST or abort)
  err_t error = ERR_OK;
  bool reading = true;  ///< false: never tcp_recved, so the window closes

  static err_t on_connected(void* arg, tcp_pcb*, err_t) {
    static_cast<Client*>(arg)->connected = true;
    return ERR_OK;
  }
  static err_t on_recv(void* arg, tcp_pcb* pcb, pbuf* p, err_t) {
    auto* c = static_cast<Client*>(arg);
    if (p == nullptr) {
      c->peer_closed = true;
      c->detach_and_close();
      return ERR_OK;
    }
    for (const pbuf* q = p; q != nullptr; q = q->next)
      c->received.append(static_cast<const char*>(q->payload), q->len);
    if (c->reading) tcp_recved(pcb, p->tot_len);
    pbuf_free(p);
    return ERR_OK;
  }
  static void on_err(void* arg, err_t err) {
    auto* c = static_cast<Client*>(arg);
    c->reset = true;
    c->error = err;
    c->pcb = nullptr;  // already freed by lwIP
  }

  void detach_and_close() {
    if (pcb == nullptr) return;
    tcp_arg(pcb, nullptr);
    tcp_recv(pcb, nullptr);
    tcp_err(pcb, nullptr);
    if (tcp_close(pcb) != ERR_OK) tcp_abort(pcb);
    pcb = nullptr;
  }

  /// Call with the core lock held. `source`: another host's address (a
  /// netif of its own), as the per-address cap sees it.
  void connect(const ip_addr_t& addr, std::uint16_t port, const ip_addr_t* source = nullptr) {
    pcb = tcp_new_ip_type(IPADDR_TYPE_V4);
    ASSERT_NE(pcb, nullptr);
    if (source != nullptr) {
      ASSERT_EQ(tcp_bind(pcb, source, 0), ERR_OK);
    }
    tcp_arg(pcb, this);
    tcp_recv(pcb, &Client::on_recv);
    tcp_err(pcb, &Client::on_err);
    ASSERT_EQ(tcp_connect(pcb, &addr, port, &Client::on_connected), ERR_OK);
  }
  /// Call with the core lock held.
  void send(std::string_view text) {
    ASSERT_NE(pcb, nullptr);
    ASSERT_EQ(tcp_write(pcb, text.data(), static_cast<u16_t>(text.size()), TCP_WRITE_FLAG_COPY),
              ERR_OK);
    ASSERT_EQ(tcp_output(pcb), ERR_OK);
  }
};

/// Stands for the Pico's flash: data that never changes, which the transport
/// may send by reference.
constexpr std::size_t kAssetBytes = 50000;
const std::array<char, kAssetBytes> kAsset = [] {
  std::array<char, kAssetBytes> a{};
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<char>('A' + i % 23);
  return a;
}();
bool in_asset(const void* data, std::size_t size) {
  const auto* p = static_cast<const char*>(data);
  return p >= kAsset.data() && p + size <= kAsset.data() + kAsset.size();
}

/// A session for transport tests: 'F' starts a flood of kFloodBytes written
/// from poll() in 200-byte writes (a counting pattern, so order is checked),
/// 'Q' answers BYE and asks for the close, 'P' answers PONG, 'S' sends the
/// asset between two copied lines, 'E' turns it into an event stream (as
/// GET /api/events does to an HTTP session).
class TestSession final : public protocol::Session {
 public:
  static constexpr std::size_t kFloodBytes = 200000;
  static constexpr std::size_t kLongBytes = 300000;  // > Debian's TCP_SND_BUF (64 KB) + 1 KiB
  static inline int live = 0;
  static inline int windows = 0;

  TestSession() { ++live; }
  ~TestSession() override { --live; }
  TestSession(const TestSession&) = delete;
  TestSession& operator=(const TestSession&) = delete;

  void receive(std::string_view bytes, protocol::ByteSink& out) override {
    for (char ch : bytes) {
      if (ch == 'F') flood_left_ = kFloodBytes;
      // A command, and (X) the protocol's STOP, for the admission rule.
      if (ch == 'P' && command_arrives(false)) out.write("PONG\n");
      if (ch == 'X' && command_arrives(true)) out.write("STOPPED\n");
      if (ch == 'S') {
        out.write("HEAD\n");
        out.write(std::string_view(kAsset.data(), kAsset.size()));
        out.write("TAIL\n");
      }
      if (ch == 'Q') {
        out.write("BYE\n");
        close_ = true;
      }
      if (ch == 'E') events_ = true;
      // HTTP keep-alive as HttpSession reports it: K answered a request and
      // waits for the next, B began one.
      if (ch == 'K') between_ = true;
      if (ch == 'B') between_ = false;
      // A reply longer than lwIP's send buffer, as HttpSession writes the
      // settings schema: written again from its start for each window.
      if (ch == 'L') {
        long_pending_ = true;
        long_sent_ = 0;
        write_more(static_cast<std::size_t>(-1), out);
      }
    }
  }
  bool output_pending() const override { return long_pending_; }
  void write_more(std::size_t room, protocol::ByteSink& out) override {
    ++windows;
    protocol::WindowSink window(out, long_sent_, room, protocol::WindowSink::Cut::kBytes);
    char chunk[1000];
    for (std::size_t at = 0; at < kLongBytes; at += sizeof chunk) {
      for (std::size_t k = 0; k < sizeof chunk; ++k) chunk[k] = pattern(at + k);
      window.write(std::string_view(chunk, sizeof chunk));
    }
    long_sent_ += window.written();
    long_pending_ = long_sent_ < window.total();
  }
  bool is_event_stream() const override { return events_; }
  bool between_requests() const override { return between_; }
  void poll(Millis, protocol::ByteSink& out) override {
    for (int i = 0; i < 4 && flood_left_ > 0; ++i) {
      char chunk[200];
      const std::size_t n = std::min(sizeof(chunk), flood_left_);
      for (std::size_t k = 0; k < n; ++k) chunk[k] = pattern(sent_ + k);
      out.write(std::string_view(chunk, n));
      sent_ += n;
      flood_left_ -= n;
    }
  }
  bool wants_close() const override { return close_; }

  static char pattern(std::size_t i) { return static_cast<char>('a' + i % 26); }
  /// The first byte of `received` that is not the pattern's, or npos: the
  /// flood and the long reply arrived whole and in order.
  static std::size_t first_out_of_order(const std::string& received) {
    for (std::size_t i = 0; i < received.size(); ++i)
      if (received[i] != pattern(i)) return i;
    return std::string::npos;
  }

 private:
  std::size_t flood_left_ = 0;
  std::size_t sent_ = 0;
  bool close_ = false;
  bool events_ = false;
  bool between_ = false;
  bool long_pending_ = false;
  std::size_t long_sent_ = 0;
};

auto make_test_session() {
  return [] { return TestSession(); };
}
using TestService = StaticService<TestSession, 4, decltype(make_test_session())>;
/// Two client slots and a stop-only one, as the Pico's line ports have.
using StopOnlyService = StaticService<TestSession, 2, decltype(make_test_session()), 1>;

ServerConfig test_config(std::size_t max_clients, std::string_view reject = "busy\r\n") {
  ServerConfig config;
  config.name = "test";
  config.max_clients = max_clients;
  config.reject_message = reject;
  config.is_immutable = &in_asset;
  return config;
}

class LwipTransportTest : public ::testing::Test {
 protected:
  static constexpr int kMaxSteps = 10000;  // x 1 ms sleep: generous, never reached when passing

  void SetUp() override {
    ensure_lwip();
    CoreLock lock;
    IP4_ADDR(ip_2_ip4(&addr_), 10, 0, 0, 1);
    IP_SET_TYPE_VAL(addr_, IPADDR_TYPE_V4);
    ASSERT_TRUE(testing::add_host_netif(netif_, *ip_2_ip4(&addr_), &init_netif));
  }

  void TearDown() override {
    stop_test_service();
    CoreLock lock;
    netif_remove(&netif_);
  }

  /// Stops the server and aborts the clients under the core lock when a test
  /// ends, before the server's storage (a local of the test) goes away.
  class Served {
   public:
    explicit Served(LwipTransportTest& t) : t_(t) {}
    ~Served() {
      CoreLock lock;
      for (Client& c : t_.clients_) {
        if (c.pcb == nullptr) continue;
        tcp_arg(c.pcb, nullptr);
        tcp_recv(c.pcb, nullptr);
        tcp_err(c.pcb, nullptr);
        tcp_abort(c.pcb);
        c.pcb = nullptr;
      }
      t_.server_->stop();
      t_.server_ = nullptr;
    }
    Served(const Served&) = delete;
    Served& operator=(const Served&) = delete;

   private:
    LwipTransportTest& t_;
  };

  /// The netif sends nothing anywhere: traffic to its own address is looped
  /// back by lwIP before output() is reached.
  static err_t init_netif(netif* n) {
    n->name[0] = 't';
    n->name[1] = 'l';
    n->mtu = 1500;
    // What would go on the wire (broadcasts: the DHCP server's replies).
    n->output = [](netif*, pbuf* p, const ip4_addr_t*) -> err_t {
      std::string packet(p->tot_len, '\0');
      pbuf_copy_partial(p, packet.data(), p->tot_len, 0);
      wire().push_back(std::move(packet));
      return ERR_OK;
    };
    return ERR_OK;
  }

  [[nodiscard]] std::unique_ptr<Served> serve(TcpServer& server) {
    server_ = &server;
    CoreLock lock;
    EXPECT_TRUE(server.start());
    EXPECT_NE(server.port(), 0);
    return std::make_unique<Served>(*this);
  }

  /// The test service of `config`, serving until the test ends.
  TestService& serve_test(const ServerConfig& config) {
    test_service_.emplace(config, make_test_session());
    test_served_ = serve(test_service_->server());
    return *test_service_;
  }
  /// Stops it (clients aborted, as Served does) before any netif goes.
  void stop_test_service() {
    test_served_.reset();
    test_service_.reset();
  }

  Client& connect(const ip_addr_t* source = nullptr) {
    Client& c = clients_[client_count_++];
    {
      CoreLock lock;
      c.connect(addr_, server_->port(), source);
    }
    EXPECT_TRUE(wait([&] { return c.connected || c.reset; }));
    return c;
  }

  void send(Client& c, std::string_view text) {
    CoreLock lock;
    c.send(text);
  }

  /// Lets lwIP's thread run and polls the server (as the firmware's loop
  /// does every tick) until pred() holds, checked under the core lock.
  template <typename Pred>
  bool wait(Pred pred) {
    for (int i = 0; i < kMaxSteps; ++i) {
      {
        CoreLock lock;
        if (server_ != nullptr) server_->poll(now_ += 10);
        if (pred()) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }

  /// Packets the netif sent out, oldest first (read with the core lock held).
  static std::vector<std::string>& wire() {
    static std::vector<std::string> packets;
    return packets;
  }

  netif netif_{};
  ip_addr_t addr_{};
  TcpServer* server_ = nullptr;
  std::array<Client, 128> clients_{};
  std::size_t client_count_ = 0;
  Millis now_ = 0;
  std::optional<TestService> test_service_;
  std::unique_ptr<Served> test_served_;
};

TEST_F(LwipTransportTest, ServesWrcCommandsOverTcp) {
  testing::FakeRotator rotator(false);
  auto make = [&rotator] { return protocol::WrcSession(*rotator.controller, "test"); };
  StaticService<protocol::WrcSession, 2, decltype(make)> wrc(
      {"WRC", 0, 2, protocol::WrcSession::kTooManyConnections}, make);
  auto served = serve(wrc.server());

  Client& c = connect();
  ASSERT_TRUE(c.connected);
  send(c, "AZ?\r\n");
  EXPECT_TRUE(wait([&] { return c.received.find("\r\n") != std::string::npos; }));
  EXPECT_EQ(c.received, "OK AZ 100.0\r\n");

  // A command split over two segments is one command to the session.
  c.received.clear();
  send(c, "A");
  send(c, "Z?\r\nBOGUS\r\n");
  EXPECT_TRUE(wait([&] { return c.received.find("ERROR") != std::string::npos; }));
  EXPECT_EQ(c.received.rfind("OK AZ 100.0\r\n", 0), 0u) << c.received;
  CoreLock lock;
  EXPECT_EQ(wrc.server().client_count(), 1u);
}

TEST_F(LwipTransportTest, ConnectionsRefusalsAndErrorRepliesAreCountedForMetrics) {
  // What GET /metrics reports on the Pico W (metrics/registry.hpp).
  testing::FakeRotator rotator(false);
  metrics::Registry registry;
  auto make = [&rotator] { return protocol::WrcSession(*rotator.controller, "test"); };
  lwip_port::ServerConfig config{"WRC", 0, 1, protocol::WrcSession::kTooManyConnections};
  config.metrics = &registry;
  config.protocol = metrics::line_metric(protocol::Personality::kWrc);
  StaticService<protocol::WrcSession, 1, decltype(make)> wrc(config, make);
  auto served = serve(wrc.server());
  const metrics::ProtocolCounters& counted =
      registry.protocol(metrics::line_metric(protocol::Personality::kWrc));

  Client& a = connect();
  send(a, "AZ?\r\nBOGUS\r\nAZ 9999\r\n");
  EXPECT_TRUE(wait([&] { return a.received.find("AZIMUTH") != std::string::npos; }));
  Client& b = connect();  // one slot: refused
  EXPECT_TRUE(wait([&] { return b.peer_closed || b.reset; }));
  {
    CoreLock lock;
    EXPECT_EQ(counted.open, 1u);
    EXPECT_EQ(counted.accepted, 1u);
    EXPECT_EQ(counted.refused, 1u);
    EXPECT_EQ(counted.errors, 2u);
    a.detach_and_close();
  }
  EXPECT_TRUE(wait([&] { return counted.open == 0; }));
  CoreLock lock;
  EXPECT_EQ(registry.protocol(metrics::Protocol::kHttp).accepted, 0u);
}

TEST_F(LwipTransportTest, RefusesClientsOverTheLimitWithTheRejectMessage) {
  TestService& service = serve_test(test_config(2, "ERROR TOO MANY CONNECTIONS\r\n"));

  Client& a = connect();
  Client& b = connect();
  ASSERT_TRUE(wait([&] { return service.server().client_count() == 2; }));
  Client& c = connect();
  EXPECT_TRUE(wait([&] { return c.peer_closed || c.reset; }));
  EXPECT_EQ(c.received, "ERROR TOO MANY CONNECTIONS\r\n");
  EXPECT_TRUE(c.peer_closed) << "a refused client gets a FIN after the message, not a reset";
  {
    CoreLock lock;
    EXPECT_EQ(service.server().client_count(), 2u);
    EXPECT_EQ(service.server().stats().rejected, 1u);
    EXPECT_EQ(TestSession::live, 2);
  }

  // The accepted clients still work, and a slot freed by a close is reused.
  send(a, "P");
  EXPECT_TRUE(wait([&] { return a.received == "PONG\n"; }));
  {
    CoreLock lock;
    b.detach_and_close();
  }
  EXPECT_TRUE(wait([&] { return service.server().client_count() == 1; }));
  Client& d = connect();
  send(d, "P");
  EXPECT_TRUE(wait([&] { return d.received == "PONG\n"; }));
  CoreLock lock;
  EXPECT_EQ(service.server().client_count(), 2u);
  EXPECT_EQ(TestSession::live, 2);
}

TEST_F(LwipTransportTest, PeerCloseReleasesTheSession) {
  TestService& service = serve_test(test_config(4));
  Client& c = connect();
  ASSERT_TRUE(wait([&] { return TestSession::live == 1; }));
  {
    CoreLock lock;
    c.detach_and_close();
  }
  EXPECT_TRUE(wait([&] { return service.server().client_count() == 0; }));
  CoreLock lock;
  EXPECT_EQ(TestSession::live, 0);
  EXPECT_EQ(service.server().stats().closed, 1u);
}

TEST_F(LwipTransportTest, SessionCloseFlushesTheReplyThenSendsFin) {
  TestService& service = serve_test(test_config(4));
  Client& c = connect();
  send(c, "Q");
  EXPECT_TRUE(wait([&] { return c.peer_closed || c.reset; }));
  EXPECT_TRUE(c.peer_closed);
  EXPECT_EQ(c.received, "BYE\n");
  CoreLock lock;
  EXPECT_EQ(service.server().client_count(), 0u);
  EXPECT_EQ(TestSession::live, 0);
}

TEST_F(LwipTransportTest, AReadingClientGetsTheWholeFloodInOrder) {
  TestService& service = serve_test(test_config(4));
  Client& c = connect();
  send(c, "F");
  EXPECT_TRUE(wait([&] { return c.received.size() >= TestSession::kFloodBytes || c.reset; }));
  ASSERT_EQ(c.received.size(), TestSession::kFloodBytes);
  ASSERT_EQ(TestSession::first_out_of_order(c.received), std::string::npos);
  CoreLock lock;
  EXPECT_EQ(service.server().stats().dropped_backlog, 0u);
  EXPECT_EQ(service.server().client_count(), 1u);
}

TEST_F(LwipTransportTest, AClientThatStopsReadingIsDroppedAndTheOthersCarryOn) {
  TestService& service = serve_test(test_config(4));
  Client& stalled = connect();
  Client& other = connect();
  stalled.reading = false;  // its receive window closes, then lwIP's send buffer fills
  send(stalled, "F");
  EXPECT_TRUE(wait([&] { return stalled.reset; }));
  EXPECT_EQ(stalled.error, ERR_RST);
  EXPECT_LT(stalled.received.size(), TestSession::kFloodBytes);
  {
    CoreLock lock;
    EXPECT_EQ(service.server().stats().dropped_backlog, 1u);
    EXPECT_EQ(service.server().client_count(), 1u);
    EXPECT_EQ(TestSession::live, 1);
  }
  send(other, "P");
  EXPECT_TRUE(wait([&] { return other.received == "PONG\n"; }));
}

// A reply longer than lwIP's send buffer and the output buffer together (the
// Pico's GET /api/settings/schema, 41 KB through 11.7 + 1 KB) goes out in
// windows, each written when the peer has acknowledged enough (tcp_sent, or
// the loop's poll): whole and in order, the client never dropped.
TEST_F(LwipTransportTest, AReplyLongerThanTheSendBufferGoesOutInWindows) {
  TestService& service = serve_test(test_config(1));
  TestSession::windows = 0;
  Client& c = connect();
  send(c, "L");
  ASSERT_TRUE(wait([&] { return c.received.size() >= TestSession::kLongBytes || c.reset; }));
  EXPECT_FALSE(c.reset);
  ASSERT_EQ(c.received.size(), TestSession::kLongBytes);
  EXPECT_EQ(TestSession::first_out_of_order(c.received), std::string::npos);
  CoreLock lock;
  EXPECT_GT(TestSession::windows, 4);
  EXPECT_EQ(service.server().stats().dropped_backlog, 0u);
}

TEST_F(LwipTransportTest, ImmutableDataLargerThanTheBufferGoesOutByReferenceInOrder) {
  TestService& service = serve_test(test_config(4));
  Client& c = connect();
  send(c, "S");
  const std::size_t total = 5 + kAssetBytes + 5;
  EXPECT_TRUE(wait([&] { return c.received.size() >= total || c.reset; }));
  ASSERT_EQ(c.received.size(), total);
  EXPECT_EQ(c.received.substr(0, 5), "HEAD\n");
  EXPECT_EQ(c.received.compare(5, kAssetBytes, kAsset.data(), kAssetBytes), 0);
  EXPECT_EQ(c.received.substr(5 + kAssetBytes), "TAIL\n");
  CoreLock lock;
  EXPECT_EQ(service.server().stats().dropped_backlog, 0u);
}

TEST_F(LwipTransportTest, WithoutTheImmutablePredicateALargeWriteDropsTheClient) {
  ServerConfig config = test_config(4);
  config.is_immutable = nullptr;  // 50 KB cannot be copied into a 1 KB buffer
  TestService& service = serve_test(config);
  Client& c = connect();
  send(c, "S");
  EXPECT_TRUE(wait([&] { return c.reset; }));
  CoreLock lock;
  EXPECT_EQ(service.server().stats().dropped_backlog, 1u);
  EXPECT_EQ(service.server().client_count(), 0u);
}

// --- Admission: idle clients make room, per-address cap, event streams --------

/// Other hosts: one more netif each (10.0.<n>.1/24), whose own address lwIP
/// loops back, so a client bound to it reaches the server and back.
class LwipAdmissionTest : public LwipTransportTest {
 protected:
  void SetUp() override {
    LwipTransportTest::SetUp();
    CoreLock lock;
    for (std::size_t i = 0; i < hosts_.size(); ++i) {
      ip4_addr_t a;
      IP4_ADDR(&a, 10, 0, static_cast<u8_t>(i + 1), 1);
      ip_addr_copy_from_ip4(host_addr_[i], a);
      ASSERT_TRUE(testing::add_host_netif(hosts_[i], a, &init_netif));
    }
  }
  void TearDown() override {
    stop_test_service();
    {
      CoreLock lock;
      for (netif& n : hosts_) netif_remove(&n);
    }
    LwipTransportTest::TearDown();
  }
  /// A client from host `n` (1..4); 0 is the server's own address.
  Client& connect_from(std::size_t n) { return connect(n == 0 ? nullptr : &host_addr_[n - 1]); }
  /// The Pico's loop polls every tick: the server always knows the time.
  void advance(Millis ms) {
    CoreLock lock;
    now_ += ms;
    server_->poll(now_);
  }
  bool pong(Client& c) {
    c.received.clear();
    send(c, "P");
    return wait([&] { return c.received == "PONG\n" || c.reset || c.peer_closed; }) &&
           c.received == "PONG\n";
  }

  settings::Settings settings_;  // net.idle_evict_s 60
  std::array<netif, 4> hosts_{};
  std::array<ip_addr_t, 4> host_addr_{};
};

TEST_F(LwipAdmissionTest, AFullPortServesANewcomerOnceAClientHasBeenIdleSixtySeconds) {
  ServerConfig config = test_config(2);
  config.settings = &settings_;
  TestService& service = serve_test(config);
  Client& a = connect_from(1);
  ASSERT_TRUE(pong(a));
  Client& b = connect_from(2);
  ASSERT_TRUE(pong(b));
  advance(30000);
  ASSERT_TRUE(pong(b));  // b still talks
  advance(29000);

  Client& early = connect_from(3);
  EXPECT_TRUE(wait([&] { return early.peer_closed || early.reset; }));
  EXPECT_EQ(early.received, "busy\r\n");
  advance(1000);  // a: 60 s without a byte
  Client& newcomer = connect_from(3);
  EXPECT_TRUE(pong(newcomer));
  EXPECT_TRUE(wait([&] { return a.peer_closed; }));  // a FIN, not a reset
  EXPECT_TRUE(pong(b));
  CoreLock lock;
  EXPECT_EQ(service.server().counters().refused_full, 1u);
  EXPECT_EQ(service.server().counters().evicted_idle, 1u);
  EXPECT_EQ(service.server().stats().rejected, 1u);
  EXPECT_EQ(TestSession::live, 2);
}

// As on Linux (ClientInfo::between_requests): a keep-alive connection
// waiting for its next request makes room for a newcomer at once, not after
// net.idle_evict_s; one in the middle of a request does not.
TEST_F(LwipAdmissionTest, AKeepAliveConnectionBetweenRequestsMakesRoomAtOnce) {
  ServerConfig config = test_config(2);
  config.settings = &settings_;
  TestService& service = serve_test(config);
  Client& a = connect_from(1);
  send(a, "B");
  ASSERT_TRUE(pong(a));  // a request in progress
  Client& b = connect_from(2);
  send(b, "B");
  ASSERT_TRUE(pong(b));
  advance(1000);
  Client& early = connect_from(3);
  EXPECT_TRUE(wait([&] { return early.peer_closed || early.reset; }));
  EXPECT_EQ(early.received, "busy\r\n");

  send(a, "K");  // a answered, now waiting for its next request
  ASSERT_TRUE(pong(a));
  advance(1000);  // 2 s, far below net.idle_evict_s
  Client& newcomer = connect_from(3);
  EXPECT_TRUE(pong(newcomer));
  EXPECT_TRUE(wait([&] { return a.peer_closed; }));  // a FIN: the browser opens another
  EXPECT_TRUE(pong(b));
  CoreLock lock;
  EXPECT_EQ(service.server().counters().refused_full, 1u);
  EXPECT_EQ(service.server().counters().evicted_idle, 1u);
  EXPECT_EQ(TestSession::live, 2);
}

TEST_F(LwipAdmissionTest, OneHostNeverTakesEverySlot) {
  ServerConfig config = test_config(3);
  config.settings = &settings_;  // net.max_per_address 6, kept below 3: 2
  TestService& service = serve_test(config);
  ASSERT_TRUE(pong(connect_from(1)));
  ASSERT_TRUE(pong(connect_from(1)));
  Client& third = connect_from(1);
  EXPECT_TRUE(wait([&] { return third.peer_closed || third.reset; }));
  EXPECT_EQ(third.received, "busy\r\n");
  EXPECT_TRUE(pong(connect_from(2)));  // the last slot is another host's
  CoreLock lock;
  EXPECT_EQ(service.server().counters().refused_per_address, 1u);
}

TEST_F(LwipAdmissionTest, WhenEverySlotIsTakenTheOldestEventStreamMakesRoom) {
  // The Pico's HTTP port: 4 slots, at most 2 event streams.
  ServerConfig config = test_config(4);
  config.settings = &settings_;
  config.max_event_streams = 2;
  TestService& service = serve_test(config);
  Client& s1 = connect_from(1);
  send(s1, "E");
  ASSERT_TRUE(pong(s1));  // the test session still answers; the transport counts it apart
  Client& s2 = connect_from(1);
  send(s2, "E");
  ASSERT_TRUE(pong(s2));
  Client& r1 = connect_from(2);
  ASSERT_TRUE(pong(r1));
  Client& r2 = connect_from(3);
  ASSERT_TRUE(pong(r2));
  // Every slot taken, nobody idle: STOP from a fifth client still gets in.
  Client& stop = connect_from(4);
  EXPECT_TRUE(pong(stop));
  EXPECT_TRUE(wait([&] { return s1.peer_closed; }));
  EXPECT_FALSE(s2.peer_closed);
  // Two streams again (s2, r1); a third (r2): the oldest (s2) gives way.
  send(r1, "E");
  ASSERT_TRUE(pong(r1));
  EXPECT_FALSE(s2.peer_closed);
  send(r2, "E");
  EXPECT_TRUE(wait([&] { return s2.peer_closed; }));
  EXPECT_TRUE(pong(stop));
  CoreLock lock;
  EXPECT_EQ(service.server().counters().evicted_event_stream, 2u);
  EXPECT_EQ(service.server().client_count(), 3u);
}

// --- DHCP server for the setup access point ----------------------------------

/// A DHCP client's message from `mac`: type, optional requested address.
std::string dhcp_message(std::uint8_t type, std::uint8_t mac_last, std::uint32_t requested = 0,
                         std::uint32_t server_id = 0) {
  std::string m(300, '\0');
  m[0] = 1;  // BOOTREQUEST
  m[1] = 1;
  m[2] = 6;
  m[4] = 0x12;  // xid
  m[7] = static_cast<char>(mac_last);
  const char mac[6] = {0x02, 0x00, 0x00, 0x00, 0x00, static_cast<char>(mac_last)};
  m.replace(28, 6, mac, 6);
  const char cookie[4] = {0x63, static_cast<char>(0x82), 0x53, 0x63};
  m.replace(236, 4, cookie, 4);
  std::size_t o = 240;
  auto put32 = [&](std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) m[o++] = static_cast<char>(v >> shift);
  };
  m[o++] = 53;
  m[o++] = 1;
  m[o++] = static_cast<char>(type);
  if (requested != 0) {
    m[o++] = 50;
    m[o++] = 4;
    put32(requested);
  }
  if (server_id != 0) {
    m[o++] = 54;
    m[o++] = 4;
    put32(server_id);
  }
  m[o++] = static_cast<char>(255);
  return m;
}

struct DhcpReply {
  bool ok = false;
  std::uint8_t type = 0;
  std::uint32_t your_ip = 0;
  std::uint8_t mac_last = 0;
};

/// Parses the last broadcast on the wire as IPv4 + UDP + DHCP.
DhcpReply parse_reply(const std::string& packet) {
  DhcpReply r;
  const auto u8 = [&](std::size_t i) { return static_cast<std::uint8_t>(packet[i]); };
  if (packet.size() < 20) return r;
  const std::size_t ip_header = (u8(0) & 0x0F) * 4u;
  const std::size_t d = ip_header + 8;  // UDP header
  if (packet.size() < d + 241 || u8(ip_header + 2) != 0 || u8(ip_header + 3) != 68) return r;
  const auto be32 = [&](std::size_t i) {
    return (std::uint32_t{u8(i)} << 24) | (std::uint32_t{u8(i + 1)} << 16) |
           (std::uint32_t{u8(i + 2)} << 8) | u8(i + 3);
  };
  r.your_ip = be32(d + 16);
  r.mac_last = u8(d + 28 + 5);
  for (std::size_t i = d + 240; i + 2 < packet.size() && u8(i) != 255; i += 2u + u8(i + 1)) {
    if (u8(i) == 53) r.type = u8(i + 2);
  }
  r.ok = u8(d) == 2;
  return r;
}

// Issue 29 on the lwIP transport, the same rule as on Linux: a newcomer to
// a full port gets one short exchange in which only STOP is obeyed, and a
// client that sends bytes but no command is idle.
TEST_F(LwipAdmissionTest, ANewcomerToAFullPortMaySayStopInItsOneExchange) {
  ServerConfig config = test_config(2);
  config.settings = &settings_;
  StopOnlyService service(config, make_test_session());
  auto served = serve(service.server());
  Client& a = connect_from(1);
  ASSERT_TRUE(pong(a));
  Client& b = connect_from(2);
  ASSERT_TRUE(pong(b));
  Client& asks = connect_from(3);  // anything but STOP: the busy refusal
  send(asks, "P");
  EXPECT_TRUE(wait([&] { return asks.peer_closed || asks.reset; }));
  EXPECT_EQ(asks.received, "busy\r\n");
  Client& stops = connect_from(3);
  send(stops, "X");
  EXPECT_TRUE(wait([&] { return stops.peer_closed || stops.reset; }));
  EXPECT_EQ(stops.received, "STOPPED\n");
  EXPECT_TRUE(stops.peer_closed);
  Client& silent = connect_from(3);  // nothing within the exchange's 2 s
  EXPECT_TRUE(wait([&] { return service.server().client_count() == 3; }));
  advance(2000);
  EXPECT_TRUE(wait([&] { return silent.peer_closed || silent.reset; }));
  EXPECT_EQ(silent.received, "busy\r\n");
  EXPECT_TRUE(pong(a));
  EXPECT_TRUE(pong(b));
  CoreLock lock;
  EXPECT_EQ(service.server().counters().stop_only, 3u);
}

// The Pico W's line ports have no RAM for a stop-only slot each: they share
// one (lwip_port::SharedStopOnly), held by one exchange at a time.
TEST_F(LwipAdmissionTest, TwoPortsShareOneStopOnlySlotOneExchangeAtATime) {
  lwip_port::StaticSharedStopOnly<sizeof(TestSession), alignof(TestSession)> shared;
  ServerConfig config = test_config(2);
  config.settings = &settings_;
  config.shared_stop_only = &shared;
  TestService a(config, make_test_session());
  TestService b(config, make_test_session());
  {
    CoreLock lock;
    ASSERT_TRUE(b.server().start());
  }
  auto served = serve(a.server());
  Client& a1 = connect_from(1);
  ASSERT_TRUE(pong(a1));
  Client& a2 = connect_from(2);
  ASSERT_TRUE(pong(a2));
  // Port A full: its newcomer says STOP in the shared slot.
  Client& stops = connect_from(3);
  send(stops, "X");
  EXPECT_TRUE(wait([&] { return stops.peer_closed || stops.reset; }));
  EXPECT_EQ(stops.received, "STOPPED\n");
  // A silent newcomer to A holds the shared slot for its 2 s.
  Client& holds = connect_from(3);
  EXPECT_TRUE(wait([&] { return a.server().client_count() == 3; }));
  EXPECT_EQ(shared.holder(), &a.server());
  // Port B full meanwhile: its newcomer finds the shared slot taken.
  server_ = &b.server();
  Client& b1 = connect_from(1);
  ASSERT_TRUE(pong(b1));
  Client& b2 = connect_from(2);
  ASSERT_TRUE(pong(b2));
  Client& refused = connect_from(4);
  EXPECT_TRUE(wait([&] { return refused.peer_closed || refused.reset; }));
  EXPECT_EQ(refused.received, "busy\r\n");
  // A's exchange times out; the slot is free for B's next newcomer.
  server_ = &a.server();
  advance(2000);
  EXPECT_TRUE(wait([&] { return holds.peer_closed || holds.reset; }));
  EXPECT_EQ(holds.received, "busy\r\n");
  EXPECT_EQ(shared.holder(), nullptr);
  server_ = &b.server();
  advance(0);  // the firmware's loop polls every server at the same time
  Client& b_stops = connect_from(4);
  send(b_stops, "X");
  EXPECT_TRUE(wait([&] { return b_stops.peer_closed || b_stops.reset; }));
  EXPECT_EQ(b_stops.received, "STOPPED\n");
  EXPECT_TRUE(pong(b1));
  server_ = &a.server();
  EXPECT_TRUE(pong(a1));
  CoreLock lock;
  EXPECT_EQ(a.server().counters().stop_only, 2u);
  EXPECT_EQ(b.server().counters().stop_only, 1u);
  EXPECT_EQ(b.server().counters().refused_full, 1u);
  b.server().stop();
}

TEST_F(LwipAdmissionTest, BytesThatAreNoCommandDoNotKeepASlot) {
  ServerConfig config = test_config(2);
  config.settings = &settings_;
  StopOnlyService service(config, make_test_session());
  auto served = serve(service.server());
  Client& a = connect_from(1);
  ASSERT_TRUE(pong(a));
  Client& b = connect_from(2);
  ASSERT_TRUE(pong(b));
  advance(30000);
  ASSERT_TRUE(pong(b));  // b asks: used
  for (int n = 0; n < 6; ++n) {
    send(a, "\n");  // a only keeps its connection warm
    advance(5000);
  }
  Client& newcomer = connect_from(3);  // a: 60 s without a command
  EXPECT_TRUE(pong(newcomer));
  EXPECT_TRUE(wait([&] { return a.peer_closed; }));
  EXPECT_TRUE(pong(b));
}

/// A session of personality P for a static pool, as the firmware's
/// network_services.cpp builds one.
template <protocol::Personality P>
struct MakeLineSession {
  const protocol::SessionDeps* deps;
  typename protocol::SessionOf<P>::type operator()() const {
    return protocol::SessionOf<P>::make(*deps);
  }
};
template <protocol::Personality P, std::size_t Slots>
using LineService = StaticService<typename protocol::SessionOf<P>::type, Slots, MakeLineSession<P>>;
template <protocol::Personality... Ps>
constexpr std::size_t kLargestSession =
    std::max({sizeof(typename protocol::SessionOf<Ps>::type)...});
template <protocol::Personality... Ps>
constexpr std::size_t kLargestAlign =
    std::max({alignof(typename protocol::SessionOf<Ps>::type)...});

// Issue 29 as the Pico W image is built (ports/pico_w/network_services.cpp):
// the five line ports with their slots (WRC 4, rotctld 3, GS-232, Easycomm
// and seed 2) and real sessions on one controller, sharing one STOP-only
// slot sized for the largest session. Each port is full of clients from
// other hosts that keep their connections warm (bare line ends) or ask for
// the position (a command, so never idle), for 50 s of the network's clock,
// less than net.idle_evict_s, so nobody may be dropped for a newcomer. A
// newcomer from yet another host still stops the moving rotator, on every
// port, every time, through the shared slot.
TEST_F(LwipAdmissionTest, ThePicoWsLinePortsObeyANewcomersStopWhileClientsHoldThem) {
  using protocol::Personality;
  testing::FakeRotator rotator(false);
  const protocol::SessionDeps deps{*rotator.controller, "test"};
  constexpr Personality kWrc = Personality::kWrc, kRotctld = Personality::kRotctld,
                        kGs232 = Personality::kGs232, kEasycomm = Personality::kEasycomm,
                        kSeed = Personality::kSeed;
  lwip_port::StaticSharedStopOnly<kLargestSession<kWrc, kRotctld, kGs232, kEasycomm, kSeed>,
                                  kLargestAlign<kWrc, kRotctld, kGs232, kEasycomm, kSeed>>
      shared;
  auto line_config = [&](Personality personality, std::size_t slots) {
    ServerConfig config;
    config.name = protocol::protocol_info(personality).name.data();
    config.max_clients = slots;
    config.reject_message = protocol::protocol_info(personality).refusal;
    config.settings = &settings_;
    config.shared_stop_only = &shared;
    return config;
  };
  LineService<kWrc, 4> wrc(line_config(kWrc, 4), {&deps});
  LineService<kRotctld, 3> rotctld(line_config(kRotctld, 3), {&deps});
  LineService<kGs232, 2> gs232(line_config(kGs232, 2), {&deps});
  LineService<kEasycomm, 2> easycomm(line_config(kEasycomm, 2), {&deps});
  LineService<kSeed, 2> seed(line_config(kSeed, 2), {&deps});
  struct Port {
    TcpServer* server;
    Personality personality;
    std::size_t slots;
    const char* warm;   ///< a bare line end: keeps a connection warm, not used
    const char* query;  ///< a position query: a command, so used
    const char* stop;   ///< the protocol's STOP
    int stopped = 0;
  };
  std::array<Port, 5> ports{{
      {&wrc.server(), kWrc, 4, "\r\n", "AZ?\r\n", "STOP\r\n"},
      {&rotctld.server(), kRotctld, 3, "\n", "p\n", "S\n"},
      {&gs232.server(), kGs232, 2, "\r", "C\r", "S\r"},
      {&easycomm.server(), kEasycomm, 2, "\r", "AZ\r", "SA SE\r"},
      {&seed.server(), kSeed, 2, "\r", "$Q\r", "$D\r"},
  }};
  {
    CoreLock lock;
    for (std::size_t i = 1; i < ports.size(); ++i) ASSERT_TRUE(ports[i].server->start());
  }
  auto served = serve(wrc.server());
  // Every port stops under the core lock when the test ends, however it
  // ends (`served` stops one).
  struct StopAll {
    std::array<Port, 5>& ports;
    ~StopAll() {
      CoreLock lock;
      for (Port& port : ports) port.server->stop();
    }
  } stop_all{ports};

  // The holders: one client per slot, from hosts 1..slots, the first asking
  // for the position, the others only sending line ends. The newcomers come
  // from the server's own address, another host.
  struct Holder {
    Client* client;
    const char* keep;
  };
  std::vector<Holder> holders;
  for (Port& port : ports) {
    server_ = port.server;
    for (std::size_t host = 1; host <= port.slots; ++host) {
      Client& c = connect_from(host);
      const char* keep = host == 1 ? port.query : port.warm;
      send(c, keep);
      holders.push_back({&c, keep});
    }
  }
  // The network's clock and the controller's tick, as the firmware's loop
  // runs them; pred() is checked under the core lock.
  auto pump = [&](auto pred, Millis step_ms = 0) {
    for (int i = 0; i < kMaxSteps; ++i) {
      {
        CoreLock lock;
        now_ += step_ms;
        for (Port& port : ports) port.server->poll(now_);
        if (pred()) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  };
  for (Port& port : ports)
    ASSERT_TRUE(pump([&] { return port.server->client_count() == port.slots; }));
  auto driving = [&] { return rotator.az.drive.cw() || rotator.az.drive.ccw(); };

  constexpr int kTries = 20;
  for (int t = 0; t < kTries * static_cast<int>(ports.size()); ++t) {
    Port& port = ports[static_cast<std::size_t>(t) % ports.size()];  // in turn: one shared slot
    for (Holder& h : holders) send(*h.client, h.keep);               // the holders keep at it
    ASSERT_TRUE(pump([] { return true; }, 500));
    bool turning = false;
    {
      CoreLock lock;  // someone's go-to: the rotator turns
      rotator.az.set_deg(100);
      turning = rotator.controller->go_to(300.0f, std::nullopt) == Error::kOk;
      rotator.run_ms(100);
      turning = turning && driving();
    }
    ASSERT_TRUE(turning) << "try " << t;
    server_ = port.server;
    Client& newcomer = connect_from(0);
    send(newcomer, port.stop);
    EXPECT_TRUE(pump([&] { return newcomer.peer_closed || newcomer.reset; }));
    CoreLock lock;
    rotator.run_ms(10);  // the next tick: the drive is off
    // Obeyed and answered as always (Easycomm's SA SE has no answer), never
    // the port's busy refusal; and the drive is off.
    const std::string_view refusal = protocol::protocol_info(port.personality).refusal;
    if (newcomer.peer_closed && newcomer.received != refusal && !driving())
      ++port.stopped;
    else
      ADD_FAILURE() << protocol::protocol_info(port.personality).name << " try " << t << ": "
                    << ::testing::PrintToString(newcomer.received)
                    << (driving() ? ", still driving" : "");
    rotator.run_ms(1500);  // the stop's coast and dead time
    EXPECT_FALSE(rotator.controller->status().moving());
  }
  std::printf(
      "[ measured ] Pico W line ports, each held by clients from other hosts (line ends, "
      "position queries): a newcomer's STOP stopped the moving rotator on WRC %d, rotctld %d, "
      "GS-232 %d, Easycomm %d, seed %d of %d times each\n",
      ports[0].stopped, ports[1].stopped, ports[2].stopped, ports[3].stopped, ports[4].stopped,
      kTries);
  CoreLock lock;
  for (const Port& port : ports) {
    EXPECT_EQ(port.stopped, kTries);
    EXPECT_EQ(port.server->counters().stop_only, static_cast<std::uint32_t>(kTries));
    EXPECT_EQ(port.server->counters().evicted_idle, 0u);
  }
  for (const Holder& h : holders)
    EXPECT_TRUE(h.client->pcb != nullptr && !h.client->peer_closed) << "a holder was dropped";
  EXPECT_EQ(shared.holder(), nullptr);
}

// The web port as the Pico W image builds it: four HttpSession slots, and
// over capacity the small web::HttpStopOnlySession in the line ports' shared
// slot (sized for the largest line session, as network_services.cpp makes
// it). Four hosts hold every slot by trickling a request head a byte at a
// time (issue 29's item 3), reconnecting when the 10 s deadline cuts them; a
// newcomer from another host still stops the turning rotator, every time,
// through the shared slot, and anything else it asks gets the busy 503.
TEST_F(LwipAdmissionTest, ThePicoWsWebPortObeysANewcomersStopWhileTricklersHoldIt) {
  using protocol::Personality;
  testing::FakeRotator rotator(false);
  constexpr Personality kWrc = Personality::kWrc, kRotctld = Personality::kRotctld,
                        kGs232 = Personality::kGs232, kEasycomm = Personality::kEasycomm,
                        kSeed = Personality::kSeed;
  using Shared =
      lwip_port::StaticSharedStopOnly<kLargestSession<kWrc, kRotctld, kGs232, kEasycomm, kSeed>,
                                      kLargestAlign<kWrc, kRotctld, kGs232, kEasycomm, kSeed>>;
  static_assert(sizeof(web::HttpStopOnlySession) <= sizeof(Shared::Storage));
  Shared shared;
  web::Api api{web::ApiContext{*rotator.controller, nullptr, nullptr, nullptr, "test"}};
  auto make_http = [&api] { return web::HttpSession(api); };
  auto make_stop_only = [&api] { return web::HttpStopOnlySession(api); };
  ServerConfig config;
  config.name = "web UI and REST API";
  config.max_clients = 4;
  config.reject_message = web::HttpSession::kTooManyConnections;
  config.settings = &settings_;
  config.max_event_streams = 2;
  config.shared_stop_only = &shared;
  StaticService<web::HttpSession, 4, decltype(make_http), 0, decltype(make_stop_only)> http(
      config, make_http, make_stop_only);
  auto served = serve(http.server());
  const std::string trickle_head = "GET /api/status HTTP/1.1\r\nHost: localhost\r\nX-Slow: ";
  std::array<Client*, 4> holders{};
  int reconnects = 0;
  // Every holder connected and part-way into a request; the port full.
  auto hold = [&] {
    for (std::size_t h = 0; h < holders.size(); ++h) {
      Client*& c = holders[h];
      if (c != nullptr && c->pcb != nullptr && !c->peer_closed) {
        send(*c, "x");  // one more byte: never a whole request
        continue;
      }
      if (c != nullptr) ++reconnects;
      c = &connect_from(h + 1);
      send(*c, trickle_head);
    }
    return wait([&] { return http.server().client_count() == holders.size(); });
  };
  auto driving = [&] { return rotator.az.drive.cw() || rotator.az.drive.ccw(); };
  auto exchange = [&](std::string_view request) -> Client& {
    Client& newcomer = connect_from(0);
    send(newcomer, request);
    EXPECT_TRUE(wait([&] { return newcomer.peer_closed || newcomer.reset; }));
    return newcomer;
  };

  constexpr int kTries = 20;
  int stopped = 0, refused = 0;
  for (int t = 0; t < kTries; ++t) {
    ASSERT_TRUE(hold()) << "try " << t;
    {
      CoreLock lock;  // someone's go-to: the rotator turns
      now_ += 100;
      api.poll(now_);
      rotator.az.set_deg(100);
      ASSERT_EQ(rotator.controller->go_to(300.0f, std::nullopt), Error::kOk);
      rotator.run_ms(100);
      ASSERT_TRUE(driving()) << "try " << t;
    }
    // Another request first: the busy answer, and the rotator turns on.
    Client& asks = exchange(
        "POST /api/goto HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n"
        "Content-Length: 10\r\n\r\n{\"az\":200}");
    {
      CoreLock lock;
      rotator.run_ms(10);
      if (asks.received == web::HttpSession::kTooManyConnections && driving()) ++refused;
    }
    ASSERT_TRUE(hold()) << "try " << t;
    Client& stops = exchange("POST /api/stop HTTP/1.1\r\nHost: localhost\r\n\r\n");
    CoreLock lock;
    rotator.run_ms(10);  // the next tick: the drive is off
    if (stops.peer_closed && stops.received.starts_with("HTTP/1.1 200 OK\r\n") && !driving())
      ++stopped;
    else
      ADD_FAILURE() << "try " << t << ": " << ::testing::PrintToString(stops.received)
                    << (driving() ? ", still driving" : "");
    rotator.run_ms(1500);  // the stop's coast and dead time
  }
  std::printf(
      "[ measured ] Pico W web port held by 4 hosts trickling request heads (%d reconnects after "
      "the deadline): a newcomer's POST /api/stop stopped the turning rotator %d of %d times, "
      "its POST /api/goto got the busy 503 and no move %d of %d times\n",
      reconnects, stopped, kTries, refused, kTries);
  CoreLock lock;
  EXPECT_EQ(stopped, kTries);
  EXPECT_EQ(refused, kTries);
  EXPECT_EQ(http.server().counters().stop_only, static_cast<std::uint32_t>(2 * kTries));
  EXPECT_EQ(shared.holder(), nullptr);
}

TEST(LwipStopOnlyRam, TheSlotOfAStopOnlyExchangeCostsAConnectionAndASession) {
  // Measured on this 64-bit host: an upper bound of the Pico's 32-bit sizes
  // (pointers and size_t are half as wide there). ports/pico_w/README.md.
  const std::size_t connection = sizeof(TcpServer::Connection) + TcpServer::kOutputBytes;
  std::printf(
      "[ measured ] a stop-only slot: TcpServer::Connection %zu B, and a session: WRC %zu B, "
      "rotctld %zu B, GS-232 %zu B, Easycomm %zu B, seed %zu B\n",
      connection, sizeof(protocol::WrcSession), sizeof(protocol::RotctldSession),
      sizeof(protocol::Gs232Session), sizeof(protocol::EasycommSession),
      sizeof(protocol::SeedSession));
  EXPECT_LE(connection, TcpServer::kOutputBytes + 288);  // the client's address: IPv6-wide
}

class DhcpServerTest : public LwipTransportTest {
 protected:
  static constexpr std::uint32_t kServer = 0x0A000001;  // 10.0.0.1, the netif

  void SetUp() override {
    LwipTransportTest::SetUp();
    CoreLock lock;
    ASSERT_TRUE(dhcp_.start(&netif_));
    client_ = udp_new();
    ASSERT_NE(client_, nullptr);
    ASSERT_EQ(udp_bind(client_, IP_ANY_TYPE, 68), ERR_OK);
  }
  void TearDown() override {
    {
      CoreLock lock;
      udp_remove(client_);
      dhcp_.stop();
    }
    LwipTransportTest::TearDown();
  }

  /// Sends a client message to the server (looped back: it is addressed to
  /// the netif) and returns the server's broadcast answer, if any.
  DhcpReply exchange(const std::string& message) {
    std::size_t before = 0;
    {
      CoreLock lock;
      before = wire().size();
      pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(message.size()), PBUF_RAM);
      EXPECT_NE(p, nullptr);
      pbuf_take(p, message.data(), static_cast<u16_t>(message.size()));
      EXPECT_EQ(udp_sendto(client_, p, &addr_, 67), ERR_OK);
      pbuf_free(p);
    }
    if (!wait([&] { return wire().size() > before; })) return {};
    CoreLock lock;
    return parse_reply(wire().back());
  }

  lwip_port::DhcpServer dhcp_;
  udp_pcb* client_ = nullptr;
};

TEST_F(DhcpServerTest, OffersThenAcknowledgesAnAddressPerClient) {
  const DhcpReply offer = exchange(dhcp_message(1, 0xA1));
  ASSERT_TRUE(offer.ok);
  EXPECT_EQ(offer.type, 2);               // OFFER
  EXPECT_EQ(offer.your_ip, 0x0A000010u);  // 10.0.0.16
  EXPECT_EQ(offer.mac_last, 0xA1);

  const DhcpReply ack = exchange(dhcp_message(3, 0xA1, offer.your_ip, kServer));
  ASSERT_TRUE(ack.ok);
  EXPECT_EQ(ack.type, 5);  // ACK
  EXPECT_EQ(ack.your_ip, offer.your_ip);

  // Another client gets the next address; the first keeps its own.
  EXPECT_EQ(exchange(dhcp_message(1, 0xB2)).your_ip, 0x0A000011u);
  EXPECT_EQ(exchange(dhcp_message(1, 0xA1)).your_ip, 0x0A000010u);
}

TEST_F(DhcpServerTest, RefusesAnAddressThatIsNotTheClientsLease) {
  const DhcpReply nak = exchange(dhcp_message(3, 0xC3, 0x0A000063 /* 10.0.0.99 */, kServer));
  ASSERT_TRUE(nak.ok);
  EXPECT_EQ(nak.type, 6);  // NAK
  EXPECT_EQ(nak.your_ip, 0u);
}

TEST_F(DhcpServerTest, IgnoresRequestsForAnotherServer) {
  std::size_t before = 0;
  {
    CoreLock lock;
    before = wire().size();
    const std::string request = dhcp_message(3, 0xD4, 0x0A000010, 0x0A0000FE);
    pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(request.size()), PBUF_RAM);
    ASSERT_NE(p, nullptr);
    pbuf_take(p, request.data(), static_cast<u16_t>(request.size()));
    ASSERT_EQ(udp_sendto(client_, p, &addr_, 67), ERR_OK);
    pbuf_free(p);
  }
  // lwIP handles the loopback queue in order: once this DISCOVER is answered,
  // the REQUEST before it was handled, and it must have produced nothing.
  const DhcpReply offer = exchange(dhcp_message(1, 0xE5));
  EXPECT_EQ(offer.type, 2);
  CoreLock lock;
  EXPECT_EQ(wire().size(), before + 1);
}

}  // namespace
}  // namespace rotord
