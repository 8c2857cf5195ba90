// "STOP is never locked out" (issue 12), through the real daemon and real
// sockets: each lock-out found on the old main, tried again. Other hosts are
// other loopback addresses (127.0.0.2, ...), as the per-address limit and the
// allow-list see them.
//
// The network's clock (timeouts, idle stamps, admission) is the wall clock
// plus every ms the manual clock was advanced, so the tests run it forward
// with advance_ms instead of waiting. Eviction is shown with
// net.idle_evict_s 0 (any idle client may go); the 60 s themselves are
// checked on a virtual clock in tests/unit/admission_test.cpp and tests/lwip.
// The HTTP request deadline (10 s, a constant) is advanced through, bounded,
// never timed.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "all_ports_test.hpp"
#include "daemon_process.hpp"
#include "http_client.hpp"

namespace rotord::testing {
namespace {

class Availability : public AllPortsTest {
 protected:
  /// Opens an event stream and waits for its first event.
  std::unique_ptr<TcpClient> event_stream(const std::string& from) {
    auto c = std::make_unique<TcpClient>(web, from);
    c->send("GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/event-stream\r\n\r\n");
    std::string seen;
    for (int i = 0; i < 30 && seen.find("data: {") == std::string::npos; ++i)
      seen += c->recv_once(100);
    EXPECT_NE(seen.find("data: {"), std::string::npos) << seen;
    return c;
  }
};

TEST_F(Availability, EightTricklingClientsFromOneHostLeaveRoomForStop) {
  // The old main: 8 connections sending a header byte every few seconds held
  // the port for ever (the timeout restarted on every byte); STOP got 503.
  std::vector<std::unique_ptr<TcpClient>> tricklers;
  for (int n = 0; n < 10; ++n) {
    tricklers.push_back(std::make_unique<TcpClient>(web, host(1)));
    tricklers.back()->send("POST /api/stop HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ");
  }
  // One host holds at most net.max_per_address (6) slots: the rest are
  // refused with the same 503 as a full port, at once or (one of them, a
  // stop-only exchange since issue 29, which only STOP would end sooner)
  // after 2 s.
  daemon->advance_ms(2100);
  int refused = 0;
  for (auto& t : tricklers) {
    const std::string got = t->recv_once(300);
    if (got.rfind("HTTP/1.1 503", 0) == 0) ++refused;
  }
  EXPECT_EQ(refused, 4);
  for (int round = 0; round < 3; ++round) {
    for (auto& t : tricklers) t->send("a");  // still "doing something"
    const HttpResponse stop = http_from(host(2), web, "POST", "/api/stop");
    EXPECT_EQ(stop.status, 200) << "round " << round << ": " << stop.body;
    daemon->advance_ms(1500);  // their pace, on the network's clock; not a timing
  }
}

TEST_F(Availability, TricklersFromEightHostsAreCutOffAtTheirDeadlineAndStopGetsIn) {
  // A full port of clients from eight hosts, each sending a header byte a
  // second: nobody is idle, nobody is over a per-host cap. The request
  // deadline (10 s from the first byte, whatever follows) frees them.
  std::vector<std::unique_ptr<TcpClient>> tricklers;
  for (int n = 1; n <= 8; ++n) {
    tricklers.push_back(std::make_unique<TcpClient>(web, host(n)));
    ASSERT_TRUE(tricklers.back()->connected());
    tricklers.back()->send("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ");
  }
  // The daemon takes the eight in on its own loop: ask until it answers
  // that the port is full (a bounded poll for the condition, not a wait).
  // Full, a newcomer may still say STOP (issue 29), nothing else.
  int full_status = 0;
  for (int n = 0; n < 50 && full_status != 503; ++n)
    full_status = http_from(host(9), web, "GET", "/api/status").status;
  EXPECT_EQ(full_status, 503);

  int stop_status = 0;
  std::vector<std::string> got(tricklers.size());
  for (int second = 0; second < 40 && stop_status != 200; ++second) {
    for (std::size_t i = 0; i < tricklers.size(); ++i) {
      tricklers[i]->send("a");
      got[i] += tricklers[i]->recv_once(0);
    }
    stop_status = http_from(host(9), web, "POST", "/api/stop").status;
    if (stop_status != 200) daemon->advance_ms(1000);  // the next second, on the network's clock
  }
  EXPECT_EQ(stop_status, 200);
  // They go on trickling, a byte a second of the network's clock, until the
  // deadline cuts each off (15 s at most; nobody sends to one that answered).
  const auto all_answered = [&] {
    for (const std::string& g : got)
      if (g.empty()) return false;
    return true;
  };
  for (int second = 0; second < 15 && !all_answered(); ++second) {
    for (std::size_t i = 0; i < tricklers.size(); ++i)
      if (got[i].empty()) tricklers[i]->send("a");
    daemon->advance_ms(1000);
    for (std::size_t i = 0; i < tricklers.size(); ++i) got[i] += tricklers[i]->recv_once(0);
  }
  for (std::size_t i = 0; i < tricklers.size(); ++i) {
    tricklers[i]->wait_closed(15000);
    got[i] += tricklers[i]->recv_once(0);
    EXPECT_EQ(got[i].rfind("HTTP/1.1 408", 0), 0u) << "trickler " << i << ": " << got[i];
  }
}

TEST_F(Availability, EightEventStreamsAndStopIsStillAnswered) {
  // The old main: 8 open pages (8 event streams) filled the port.
  std::vector<std::unique_ptr<TcpClient>> streams;
  for (int n = 0; n < 8; ++n) streams.push_back(event_stream(host(1)));
  const HttpResponse stop = http(web, "POST", "/api/stop");  // same host, too
  EXPECT_EQ(stop.status, 200) << stop.body;
  EXPECT_EQ(http(web, "GET", "/api/status").status, 200);

  // A ninth page: the oldest stream gives way (web.max_event_streams, 8).
  streams.push_back(event_stream(host(1)));
  EXPECT_TRUE(streams.front()->wait_closed(3000));
  for (std::size_t i = 1; i < streams.size(); ++i) {
    std::string more;
    for (int k = 0; k < 30 && more.find("data: {") == std::string::npos; ++k)
      more += streams[i]->recv_once(100);
    EXPECT_NE(more.find("data: {"), std::string::npos) << "stream " << i;
  }
}

struct LineProtocol {
  const char* name;
  int port;
  const char* query;
  const char* busy;  ///< the refusal of a full port
};

TEST_F(Availability, EightIdleClientsOnEveryLineProtocolAndANewcomerIsServed) {
  // The old main: 8 idle sockets locked every new client of a protocol out.
  set(R"({"net.idle_evict_s": 0})");
  const DaemonProcess::Ports& p = daemon->ports();
  const LineProtocol protocols[] = {
      {"WRC", p.wrc, "AZ?\n", "ERROR TOO MANY CONNECTIONS"},
      {"rotctld", p.rotctld, "p\n", "RPRT -9"},
      {"GS-232", p.gs232, "C\r", "?>"},
      {"Easycomm", p.easycomm, "AZ EL\n", "ALBUSY"},
      {"seed", seed_port, "$Q\n", "$ERR,BUSY"},
  };
  for (const LineProtocol& proto : protocols) {
    SCOPED_TRACE(proto.name);
    std::vector<std::unique_ptr<TcpClient>> idle;
    for (int n = 1; n <= 8; ++n) {
      idle.push_back(std::make_unique<TcpClient>(proto.port, host(n)));
      const std::string reply = idle.back()->ask(proto.query);
      ASSERT_FALSE(reply.empty());
      ASSERT_NE(reply, proto.busy);
    }
    daemon->advance_ms(50);  // a few ticks of the network's clock: stamped idle
    TcpClient newcomer(proto.port, host(9));
    const std::string reply = newcomer.ask(proto.query);
    EXPECT_FALSE(reply.empty());
    EXPECT_NE(reply, proto.busy);
    // The one idle longest (the first) made room; the others stay.
    EXPECT_TRUE(idle.front()->wait_closed(3000));
    EXPECT_NE(idle.back()->ask(proto.query), proto.busy);
  }
}

TEST_F(Availability, IdleClientsOnTheAllowListAreNeverDroppedSoTheNewcomerIsRefused) {
  set(R"({"net.idle_evict_s": 0, "access.control_networks": "127.0.0.0/29, 127.0.0.8"})");
  std::vector<std::unique_ptr<TcpClient>> listed;
  for (int n = 1; n <= 8; ++n) {
    listed.push_back(std::make_unique<TcpClient>(daemon->ports().wrc, host(n)));
    ASSERT_EQ(listed.back()->ask("AZ?\n").rfind("OK AZ", 0), 0u);
  }
  TcpClient stranger(daemon->ports().wrc, host(20));
  EXPECT_EQ(stranger.ask("AZ?\n"), "ERROR TOO MANY CONNECTIONS");  // only STOP would do
  EXPECT_TRUE(stranger.wait_closed());
  for (auto& c : listed) EXPECT_EQ(c->ask("SPEED?\n"), "OK SPEED 100");
}

}  // namespace
}  // namespace rotord::testing
