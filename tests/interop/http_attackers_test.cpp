// HTTP STOP under hosts that trickle their requests and reconnect as soon as
// the deadline cuts them (issue 29, item 3), through the real daemon; the
// network's timeouts run on the manual clock (--clock manual advances them).
// Prints how many of the owner's twenty POST /api/stop were answered.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"

namespace rotord::testing {
namespace {

std::string host(int n) {
  return "127.0.0." + std::to_string(n);
}

constexpr const char* kHead = "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ";

class HttpAttackers : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    web = daemon->ports().web;
  }
  struct Trickler {
    std::string from;
    std::unique_ptr<TcpClient> client;
    int reconnects = 0;
  };
  /// Each trickler sends one more byte of its head; one the server closed
  /// (the deadline's 408, or a refusal) comes back at once.
  void trickle(std::vector<Trickler>& tricklers) {
    for (Trickler& t : tricklers) {
      if (t.client && !t.client->closed_now()) {
        t.client->send("a");
        continue;
      }
      t.client = std::make_unique<TcpClient>(web, t.from);
      t.client->send(kHead);
      ++t.reconnects;
    }
  }
  /// Opens an event stream from `from`.
  std::unique_ptr<TcpClient> event_stream(const std::string& from) {
    auto c = std::make_unique<TcpClient>(web, from);
    c->send("GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/event-stream\r\n\r\n");
    return c;
  }
  /// 40 s of the attack: a byte a second from every trickler, the owner's
  /// STOP every 2 s. Returns how many of the 20 STOPs were answered 200.
  int attack(std::vector<Trickler>& tricklers) {
    int answered = 0;
    for (int second = 0; second < 40; ++second) {
      trickle(tricklers);
      if (second % 2 == 1) {
        const HttpResponse stop = http_from(host(1), web, "POST", "/api/stop");
        if (stop.status == 200) ++answered;
      }
      daemon->advance_ms(1000);
    }
    return answered;
  }

  std::unique_ptr<DaemonProcess> daemon;
  int web = 0;
};

TEST_F(HttpAttackers, EightReconnectingTricklersNeverLockStopOut) {
  std::vector<Trickler> tricklers;
  for (int n = 2; n <= 9; ++n) tricklers.push_back({host(n), nullptr});
  const int answered = attack(tricklers);
  int reconnects = 0;
  for (const Trickler& t : tricklers) reconnects += t.reconnects;
  std::printf(
      "[ measured ] 8 hosts trickling and reconnecting (%d connections in 40 s): POST "
      "/api/stop answered for the owner %d of 20\n",
      reconnects, answered);
  EXPECT_EQ(answered, 20);
  EXPECT_GE(reconnects, 8 * 4);  // the 10 s deadline cut each of them again and again
}

TEST_F(HttpAttackers, FortyEightTricklersAndEventStreamsNeverLockStopOut) {
  std::vector<Trickler> tricklers;
  for (int n = 2; n <= 9; ++n)
    for (int k = 0; k < 6; ++k) tricklers.push_back({host(n), nullptr});
  std::vector<std::unique_ptr<TcpClient>> streams;
  for (int n = 2; n <= 9; ++n) streams.push_back(event_stream(host(n)));
  const int answered = attack(tricklers);
  std::printf(
      "[ measured ] 48 trickling connections from 8 hosts and 8 event streams: POST "
      "/api/stop answered for the owner %d of 20\n",
      answered);
  EXPECT_EQ(answered, 20);
}

TEST_F(HttpAttackers, OverCapacityOnlyStopIsServed) {
  std::vector<Trickler> tricklers;
  for (int n = 2; n <= 9; ++n) tricklers.push_back({host(n), nullptr});
  trickle(tricklers);
  daemon->advance_ms(100);
  // Full: a newcomer's status request gets the busy 503, its STOP a 200.
  EXPECT_EQ(http_from(host(1), web, "GET", "/api/status").status, 503);
  EXPECT_EQ(http_from(host(1), web, "POST", "/api/goto", R"({"az": 100})").status, 503);
  EXPECT_EQ(http_from(host(1), web, "POST", "/api/stop").status, 200);
}

}  // namespace
}  // namespace rotord::testing
