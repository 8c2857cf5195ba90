// The Linux TcpServer's admission on a clock the test owns: real loopback
// sockets, but the `now` the daemon's tick would pass to poll() is chosen
// here, so "idle for 60 s" takes no minute (the interop tests can only show
// net.idle_evict_s 0, the network running on the wall clock).
#include "tcp_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace rotord::linux_port {
namespace {

/// 'P' answers PONG; it is a command the protocol knows (a client that
/// sends it is in use), and not STOP.
class PingSession final : public protocol::Session {
 public:
  void receive(std::string_view bytes, protocol::ByteSink& out) override {
    for (char c : bytes) {
      if (c == 'P' && command_arrives(false)) out.write("PONG\n");
    }
  }
};

/// A blocking loopback client from a chosen source address.
class Client {
 public:
  Client(std::uint16_t port, const char* source) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in local{};
    local.sin_family = AF_INET;
    ::inet_pton(AF_INET, source, &local.sin_addr);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(port);
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&local), sizeof(local)) != 0 ||
        ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~Client() {
    if (fd_ >= 0) ::close(fd_);
  }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  void send(const char* text) { ::send(fd_, text, std::strlen(text), MSG_NOSIGNAL); }
  /// What arrived without waiting; closed_ once the peer closed.
  void read() {
    pollfd p{fd_, POLLIN, 0};
    while (::poll(&p, 1, 0) > 0) {
      char buf[256];
      const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
      if (n <= 0) {
        closed = true;
        return;
      }
      got.append(buf, static_cast<std::size_t>(n));
    }
  }
  std::string got;
  bool closed = false;

 private:
  int fd_ = -1;
};

class TcpServerAdmission : public ::testing::Test {
 protected:
  void SetUp() override {
    ServiceConfig config;
    config.name = "test";
    config.max_clients = 4;
    config.reject_message = "BUSY\n";
    config.make_session = [] { return std::make_unique<PingSession>(); };
    config.settings = &settings;
    server = std::make_unique<TcpServer>(io, asio::ip::make_address("127.0.0.1"), config);
    server->poll(now);
  }
  /// The daemon polls every tick: its servers always know the time.
  void advance(Millis ms) {
    now += ms;
    server->poll(now);
  }
  /// Runs the loop (and the server's poll at the test's `now`) until pred()
  /// holds; bounded by a step count.
  template <typename Pred>
  bool run_until(Pred pred) {
    for (int i = 0; i < 2000; ++i) {
      io.run_for(std::chrono::milliseconds(1));
      server->poll(now);
      for (auto& c : clients) c->read();
      if (pred()) return true;
    }
    return false;
  }
  Client& connect(const char* source) {
    clients.push_back(std::make_unique<Client>(server->port(), source));
    return *clients.back();
  }
  bool ping(Client& c) {
    c.got.clear();
    c.send("P");
    return run_until([&] { return c.got == "PONG\n" || c.closed; }) && c.got == "PONG\n";
  }

  settings::Settings settings;  // net.idle_evict_s 60, net.max_per_address 6 (3 below 4)
  asio::io_context io;
  std::unique_ptr<TcpServer> server;
  std::vector<std::unique_ptr<Client>> clients;
  Millis now = 1000;
};

TEST_F(TcpServerAdmission, AFullPortServesANewcomerOnceAClientHasBeenIdleSixtySeconds) {
  const char* hosts[] = {"127.0.0.1", "127.0.0.2", "127.0.0.3", "127.0.0.4"};
  for (const char* h : hosts) ASSERT_TRUE(ping(connect(h)));
  advance(30000);
  ASSERT_TRUE(ping(*clients[0]));  // the first one still talks
  advance(29990 - net::kStopOnlyExchangeMs);

  // A newcomer to a full port first gets the STOP-only exchange
  // (net/admission.hpp); silent, it is refused when that ends.
  Client& early = connect("127.0.0.5");
  io.run_for(std::chrono::milliseconds(100));  // accepted
  advance(net::kStopOnlyExchangeMs);           // the others: idle 60 s less a tick
  ASSERT_TRUE(run_until([&] { return early.closed; }));
  EXPECT_EQ(early.got, "BUSY\n");
  EXPECT_EQ(server->counters().stop_only, 1u);

  advance(10);  // 60 s
  Client& newcomer = connect("127.0.0.6");
  EXPECT_TRUE(ping(newcomer));
  // The one idle longest made room: the second (connected before 3 and 4).
  EXPECT_TRUE(run_until([&] { return clients[1]->closed; }));
  EXPECT_FALSE(clients[0]->closed);
  EXPECT_TRUE(ping(*clients[0]));
  EXPECT_EQ(server->counters().evicted_idle, 1u);
  EXPECT_EQ(server->client_count(), 4u);
}

TEST_F(TcpServerAdmission, OneHostHoldsAtMostThreeOfFourAndItsNewcomerReplacesItsIdlest) {
  for (int n = 0; n < 3; ++n) ASSERT_TRUE(ping(connect("127.0.0.1")));
  Client& fourth = connect("127.0.0.1");
  io.run_for(std::chrono::milliseconds(100));  // accepted
  advance(net::kStopOnlyExchangeMs);           // its STOP-only exchange ends, silent
  ASSERT_TRUE(run_until([&] { return fourth.closed; }));
  EXPECT_EQ(fourth.got, "BUSY\n");
  EXPECT_EQ(server->counters().stop_only, 1u);  // at its cap: the STOP-only exchange
  EXPECT_TRUE(ping(connect("127.0.0.2")));      // another host still gets in

  // The host's old connections went quiet (say it rebooted): after 60 s its
  // newcomer replaces its own idlest, even with the port not full.
  advance(60000);
  Client& back = connect("127.0.0.1");
  EXPECT_TRUE(ping(back));
  EXPECT_TRUE(run_until([&] { return clients[0]->closed; }));
  EXPECT_EQ(server->counters().evicted_idle, 1u);
}

TEST_F(TcpServerAdmission, AClientOnTheAllowListIsNeverDroppedForAStranger) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "127.0.0.0/30").error,
            Error::kOk);  // 127.0.0.1 - .3 (and .0)
  const char* hosts[] = {"127.0.0.1", "127.0.0.2", "127.0.0.3", "127.0.0.4"};
  for (const char* h : hosts) ASSERT_TRUE(ping(connect(h)));
  advance(3600000);
  Client& stranger = connect("127.0.0.9");
  EXPECT_TRUE(ping(stranger));
  EXPECT_TRUE(run_until([&] { return clients[3]->closed; }));  // 127.0.0.4, not listed
  Client& another = connect("127.0.0.10");
  io.run_for(std::chrono::milliseconds(100));  // accepted
  advance(net::kStopOnlyExchangeMs);           // its STOP-only exchange ends, silent
  ASSERT_TRUE(run_until([&] { return another.closed; }));
  EXPECT_EQ(another.got, "BUSY\n");  // the stranger is not idle yet, the rest listed
}

}  // namespace
}  // namespace rotord::linux_port
