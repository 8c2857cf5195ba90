// STOP and the owner survive attackers who keep talking (issue 29, items 1
// and 2), through the real daemon on the manual clock: eight attackers from
// eight addresses hold every slot of a line port, the owner (127.0.0.1)
// tries STOP twenty times. Each test prints how many of the twenty were
// obeyed, per port.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "all_ports_test.hpp"
#include "both_axes.hpp"
#include "daemon_process.hpp"
#include "http_client.hpp"

namespace rotord::testing {
namespace {

struct LineProtocol {
  const char* name;
  int port;
  const char* stop;   ///< the protocol's STOP
  const char* query;  ///< a read-only query with a one-line reply
  const char* move;   ///< a move to az 100
  const char* moved;  ///< the reply to the move when allowed ("" for none)
  const char* busy;   ///< the refusal of a full port
};

class LineAttackers : public AllPortsTest {
 protected:
  void SetUp() override {
    AllPortsTest::SetUp();
    if (HasFatalFailure()) return;
    const DaemonProcess::Ports& p = daemon->ports();
    protocols = {
        {"WRC", p.wrc, "STOP\n", "AZ?\n", "AZ 100\n", "OK AZ 100.00", "ERROR TOO MANY CONNECTIONS"},
        {"rotctld", p.rotctld, "S\n", "_\n", "P 100 10\n", "RPRT 0", "RPRT -9"},
        {"GS-232", p.gs232, "S\r", "C\r", "M100\r", "", "?>"},
        {"Easycomm", p.easycomm, "SA SE\n", "AZ\n", "AZ100.0 EL10.0\n", "", "ALBUSY"},
        {"seed", seed_port, "$D\n", "$Q\n", "$E\n", "$OK,E", "$ERR,BUSY"},
    };
  }
  bool stopped() { return both_axes_stopped(web); }
  void start_moving(int round) { start_moving_both_axes(*daemon, web, round); }
  /// The owner's try: a new connection, STOP, then whether it was obeyed.
  bool owner_stops(const LineProtocol& proto) {
    TcpClient owner(proto.port, host(1));
    if (!owner.connected() || !owner.send(proto.stop)) return false;
    // Replies (where the protocol has one) come before the next poll.
    owner.recv_once(200);
    daemon->advance_ms(100);
    return stopped();
  }
  /// Attackers that went (evicted, or at the end of their exchange) come back.
  void reconnect(std::vector<std::unique_ptr<TcpClient>>& attackers, const LineProtocol& proto,
                 int first_host) {
    for (std::size_t i = 0; i < attackers.size(); ++i) {
      if (!attackers[i]->closed_now()) continue;
      attackers[i] =
          std::make_unique<TcpClient>(proto.port, host(first_host + static_cast<int>(i)));
    }
  }

  std::vector<LineProtocol> protocols;
};

TEST_F(LineAttackers, ClientsThatOnlySendLineEndsNeverLockStopOut) {
  // Item 1: eight clients from eight addresses each send a bare line end
  // every 5 s (the manual clock), and reconnect whenever they are closed.
  for (const char* networks : {"", "127.0.0.1/32"}) {
    set(std::string(R"({"access.control_networks": ")") + networks + "\"}");
    for (const LineProtocol& proto : protocols) {
      SCOPED_TRACE(std::string(proto.name) + " networks '" + networks + "'");
      std::vector<std::unique_ptr<TcpClient>> attackers;
      for (int n = 2; n <= 9; ++n) {
        attackers.push_back(std::make_unique<TcpClient>(proto.port, host(n)));
        ASSERT_TRUE(attackers.back()->connected());
      }
      daemon->advance_ms(100);  // the daemon has taken them in
      int obeyed = 0;
      for (int round = 0; round < 20; ++round) {
        reconnect(attackers, proto, 2);
        for (auto& a : attackers) a->send("\n");
        daemon->advance_ms(100);
        start_moving(round);
        if (owner_stops(proto)) ++obeyed;
        daemon->advance_ms(5000);  // the attackers' pace
      }
      std::printf(
          "[ measured ] warm line ends x8, access.control_networks '%s', %s: STOP "
          "obeyed for the owner %d of 20\n",
          networks, proto.name, obeyed);
      EXPECT_EQ(obeyed, 20);
      if (networks[0] != '\0') {
        // Listed, the owner is served in full at once: a stranger gives way.
        TcpClient owner(proto.port, host(1));
        const std::string reply = owner.ask(proto.query);
        EXPECT_NE(reply, proto.busy);
        EXPECT_FALSE(reply.empty());
      }
    }
  }
}

TEST_F(LineAttackers, SilentClientsInsideTheAllowListGiveWayToTheListedOwner) {
  // Item 2: a home network on the list, eight silent clients on it, even
  // with net.idle_evict_s 0 they used to lock the owner out of every port.
  set(R"({"access.control_networks": "127.0.0.0/8", "net.idle_evict_s": 0})");
  for (const LineProtocol& proto : protocols) {
    SCOPED_TRACE(proto.name);
    // 127.0.0.2 is a tracking program that asks every round: useful. The
    // other seven only hold their connections.
    auto tracker = std::make_unique<TcpClient>(proto.port, host(2));
    ASSERT_FALSE(tracker->ask(proto.query).empty());
    std::vector<std::unique_ptr<TcpClient>> silent;
    for (int n = 3; n <= 9; ++n) silent.push_back(std::make_unique<TcpClient>(proto.port, host(n)));
    daemon->advance_ms(100);
    int obeyed = 0;
    int moved = 0;
    for (int round = 0; round < 20; ++round) {
      reconnect(silent, proto, 3);
      daemon->advance_ms(1000);
      const std::string tracked = tracker->ask(proto.query);
      ASSERT_FALSE(tracked.empty()) << "round " << round << ": the tracker was dropped";
      ASSERT_NE(tracked, proto.busy);
      start_moving(round);
      if (owner_stops(proto)) ++obeyed;
      // A whole session, not only STOP: the owner moves the rotator.
      TcpClient owner(proto.port, host(1));
      if (proto.moved[0] != '\0') {
        if (owner.ask(proto.move) == proto.moved) ++moved;
      } else {
        owner.send(proto.move);
        const std::string none = owner.recv_once(200);
        daemon->advance_ms(100);
        if (none.find(proto.busy) == std::string::npos && !stopped()) ++moved;
      }
      http(web, "POST", "/api/stop");
    }
    std::printf(
        "[ measured ] 8 silent listed clients, %s: STOP obeyed for the listed owner %d "
        "of 20, a move %d of 20\n",
        proto.name, obeyed, moved);
    EXPECT_EQ(obeyed, 20);
    EXPECT_EQ(moved, 20);
  }
}

TEST_F(LineAttackers, AStrangerToAFullPortMaySayStopButNothingElse) {
  // Every slot held by listed clients: a stranger gets one short exchange.
  set(R"({"access.control_networks": "127.0.0.0/29, 127.0.0.8"})");
  const LineProtocol& wrc = protocols[0];
  std::vector<std::unique_ptr<TcpClient>> listed;
  for (int n = 1; n <= 8; ++n) {
    listed.push_back(std::make_unique<TcpClient>(wrc.port, host(n)));
    ASSERT_EQ(listed.back()->ask("AZ?\n").rfind("OK AZ", 0), 0u);
  }
  {
    TcpClient stranger(wrc.port, host(20));
    EXPECT_EQ(stranger.ask("AZ?\n"), "ERROR TOO MANY CONNECTIONS");
    EXPECT_TRUE(stranger.wait_closed());
  }
  {
    start_moving(0);
    TcpClient stranger(wrc.port, host(20));
    EXPECT_EQ(stranger.ask("STOP\n"), "OK STOP");
    EXPECT_TRUE(stranger.wait_closed());  // one exchange only
    daemon->advance_ms(100);
    EXPECT_TRUE(stopped());
  }
  {
    // Saying nothing: the busy refusal at the exchange's deadline (2 s).
    TcpClient stranger(wrc.port, host(21));
    daemon->advance_ms(2100);
    std::string line;
    ASSERT_TRUE(stranger.read_line(line));
    EXPECT_EQ(line, "ERROR TOO MANY CONNECTIONS");
    EXPECT_TRUE(stranger.wait_closed());
  }
  for (auto& c : listed) EXPECT_EQ(c->ask("SPEED?\n"), "OK SPEED 100");
}

}  // namespace
}  // namespace rotord::testing
