// IPv6 too (issue 29, "Must hold"), through the real daemon on its default
// address (::, IPv6 and IPv4 on one socket per port) and the manual clock:
// every port answers over [::1] and 127.0.0.1; STOP gets through trickling
// attackers to an owner on [::1] (a line port, HTTP); an IPv6 host is held to
// the per-address cap; the allow-list takes IPv6 prefixes and matches an
// IPv4 client against an IPv6-written entry (::ffff:127.0.0.1); password
// guesses over IPv6 spend the strangers' budget. Each test skips on a machine
// without the IPv6 loopback. The measured figures are printed.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "both_axes.hpp"
#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr const char* kOwner6 = "::1";

std::string host(int n) {
  return "127.0.0." + std::to_string(n);
}

/// One UDP datagram from [::1] to [::1]:port, and the reply that comes back
/// to [::1]:reply_port within timeout_ms ("" for none).
std::string udp6(int port, int reply_port, const std::string& datagram, int timeout_ms = 2000) {
  const int in = ::socket(AF_INET6, SOCK_DGRAM, 0);
  const int out = ::socket(AF_INET6, SOCK_DGRAM, 0);
  sockaddr_in6 a{};
  a.sin6_family = AF_INET6;
  a.sin6_addr = in6addr_loopback;
  a.sin6_port = htons(static_cast<uint16_t>(reply_port));
  std::string reply;
  if (in >= 0 && out >= 0 && ::bind(in, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
    a.sin6_port = htons(static_cast<uint16_t>(port));
    ::sendto(out, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
    pollfd p{in, POLLIN, 0};
    char buf[512];
    if (::poll(&p, 1, timeout_ms) == 1) {
      const ssize_t n = ::recv(in, buf, sizeof buf, 0);
      if (n > 0) reply.assign(buf, static_cast<std::size_t>(n));
    }
  }
  if (in >= 0) ::close(in);
  if (out >= 0) ::close(out);
  return reply;
}

class Ipv6 : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!ipv6_loopback()) GTEST_SKIP() << "this machine has no IPv6 loopback (::1)";
    seed_port = free_port();
    pst_port = free_port();
    dir = make_temp_dir("rotord-ipv6");
    std::ofstream(dir + "/settings.json")
        << R"({"pst.enabled": true, "pst.port": )" << pst_port << "}\n";
    // The daemon's default address, ::.
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--seed-port", std::to_string(seed_port), "--bind",
        "::", "--config", dir + "/settings.json", "--log-level", "debug"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    web = daemon->ports().web;
  }
  void TearDown() override {
    daemon.reset();
    if (!dir.empty()) std::filesystem::remove_all(dir);
  }
  void set(const std::string& json) {
    const HttpResponse r = http_from(kOwner6, web, "POST", "/api/settings", json);
    ASSERT_EQ(r.status, 200) << r.body;
  }
  bool stopped() { return both_axes_stopped(web); }
  void start_moving(int round) { start_moving_both_axes(*daemon, web, round); }
  /// Twenty rounds: the attackers send a bare line end (reconnecting when
  /// closed), the rotator is set moving, `owner` says STOP on a new
  /// connection; then 5 s pass. Returns how many STOPs were obeyed.
  int stop_rounds(int port, const std::vector<std::string>& from, const std::string& owner) {
    std::vector<std::unique_ptr<TcpClient>> attackers;
    for (const std::string& f : from) attackers.push_back(std::make_unique<TcpClient>(port, f));
    daemon->advance_ms(100);
    int obeyed = 0;
    for (int round = 0; round < 20; ++round) {
      for (std::size_t i = 0; i < attackers.size(); ++i) {
        if (attackers[i]->closed_now()) attackers[i] = std::make_unique<TcpClient>(port, from[i]);
        attackers[i]->send("\n");
      }
      daemon->advance_ms(100);
      start_moving(round);
      TcpClient stop(port, owner);
      if (stop.connected() && stop.send("STOP\n")) {
        stop.recv_once(200);
        daemon->advance_ms(100);
        if (stopped()) ++obeyed;
      }
      daemon->advance_ms(5000);
    }
    return obeyed;
  }

  /// `seconds` of the network's clock: a wrong password every 2 s from
  /// `attackers` in turn, and the owner's right one every 6 s from `owner`
  /// (within the listed budget of 10 a minute). Prints and returns the
  /// guesses checked; `owner_in` how often the owner got in (of seconds / 6).
  int guess_attack(const std::vector<std::string>& attackers, const std::string& owner, int seconds,
                   int& owner_in, const char* what) {
    const auto wall_start = std::chrono::steady_clock::now();
    int checked = 0;
    int held_back = 0;
    owner_in = 0;
    for (int second = 0; second < seconds; second += 2) {
      const std::string& from = attackers[static_cast<std::size_t>(second / 2) % attackers.size()];
      const std::string guess = R"({"password": "guess )" + std::to_string(second) + "\"}";
      const int s = http_from(from, web, "POST", "/api/login", guess).status;
      checked += s == 401;
      held_back += s == 429;
      if (second % 6 == 0 &&
          http_from(owner, web, "POST", "/api/login", R"({"password": "correct horse"})").status ==
              200)
        ++owner_in;
      daemon->advance_ms(2000);
    }
    // The network's clock is the manual clock's advances and the wall
    // clock's time as the checks ran.
    minutes =
        (seconds +
         std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()) /
        60.0;
    std::printf(
        "[ measured ] %s: %d guesses checked in %.2f min of the network's clock (%.1f a minute "
        "in total), %d held back; the listed owner %s logged in %d of %d\n",
        what, checked, minutes, checked / minutes, held_back, owner.c_str(), owner_in, seconds / 6);
    return checked;
  }

  double minutes = 0;  ///< guess_attack's length on the network's clock
  std::string dir;
  std::unique_ptr<DaemonProcess> daemon;
  int web = 0;
  int seed_port = 0;
  int pst_port = 0;
};

TEST_F(Ipv6, EveryPortAnswersOverIpv6AndIpv4ByDefault) {
  const DaemonProcess::Ports& p = daemon->ports();
  struct Line {
    const char* name;
    int port;
    const char* query;
    const char* starts;
  };
  const Line lines[] = {{"WRC", p.wrc, "AZ?\n", "OK AZ"},
                        {"rotctld", p.rotctld, "_\n", "rotord"},
                        {"GS-232", p.gs232, "C\r", "AZ="},
                        {"Easycomm", p.easycomm, "AZ\n", "AZ"},
                        {"seed", seed_port, "$Q\n", "$"}};
  for (const Line& line : lines) {
    for (const std::string& from : {std::string(kOwner6), host(1)}) {
      TcpClient c(line.port, from);
      ASSERT_TRUE(c.connected()) << line.name << " from " << from;
      const std::string reply = c.ask(line.query);
      EXPECT_EQ(reply.rfind(line.starts, 0), 0u) << line.name << " from " << from << ": " << reply;
    }
  }
  EXPECT_EQ(http_from(kOwner6, web, "GET", "/api/status").status, 200);
  EXPECT_EQ(http_from(host(1), web, "GET", "/api/status").status, 200);
  // The log names an IPv4 client of the dual-stack socket as IPv4.
  EXPECT_TRUE(daemon->wait_for_output("WRC text protocol: 127.0.0.1:")) << daemon->output();
  EXPECT_TRUE(daemon->wait_for_output("WRC text protocol: [::1]:")) << daemon->output();
  EXPECT_EQ(daemon->output().find("::ffff:127.0.0.1"), std::string::npos);
  // UDP: PstRotator over IPv6, its answer back to the sender's [::1].
  const std::string reply = udp6(pst_port, pst_port + 1, "<PST>AZ?</PST>");
  EXPECT_EQ(reply.rfind("AZ:", 0), 0u) << reply << "\n" << daemon->output();
}

TEST_F(Ipv6, StopOnALinePortReachesAnIpv6OwnerThroughWarmAttackers) {
  // Eight IPv4 attackers keep the WRC port warm; the owner on [::1] says STOP.
  std::vector<std::string> v4;
  for (int n = 2; n <= 9; ++n) v4.push_back(host(n));
  for (const char* networks : {"", "::1/128"}) {
    set(std::string(R"({"access.control_networks": ")") + networks + "\"}");
    const int obeyed = stop_rounds(daemon->ports().wrc, v4, kOwner6);
    std::printf(
        "[ measured ] 8 IPv4 hosts warming WRC, access.control_networks '%s': STOP over [::1] "
        "obeyed %d of 20\n",
        networks, obeyed);
    EXPECT_EQ(obeyed, 20);
  }
  // Listed by its IPv6 prefix, the owner is served in full (a stranger gives
  // way), and may move the rotator; a stranger may not.
  std::vector<std::unique_ptr<TcpClient>> warm;
  for (const std::string& f : v4)
    warm.push_back(std::make_unique<TcpClient>(daemon->ports().wrc, f));
  daemon->advance_ms(100);
  TcpClient owner(daemon->ports().wrc, kOwner6);
  EXPECT_EQ(owner.ask("AZ 100\n"), "OK AZ 100.00");
  set(R"({"access.control_networks": "fd00::/8, 2001:db8::/32"})");
  TcpClient later(daemon->ports().wrc, kOwner6);
  EXPECT_NE(later.ask("AZ 120\n").rfind("OK AZ", 0), 0u);  // read-only now
}

TEST_F(Ipv6, OneIpv6HostIsHeldToThePerAddressCap) {
  // Eight connections from [::1], warm: the host holds at most
  // net.max_per_address of the eight slots, so IPv4 hosts still get in.
  std::vector<std::string> v6(8, kOwner6);
  const int obeyed = stop_rounds(daemon->ports().wrc, v6, host(1));
  std::printf("[ measured ] 8 warm connections from [::1]: STOP from 127.0.0.1 obeyed %d of 20\n",
              obeyed);
  EXPECT_EQ(obeyed, 20);
  std::vector<std::unique_ptr<TcpClient>> held;
  for (int n = 0; n < 8; ++n)
    held.push_back(std::make_unique<TcpClient>(daemon->ports().wrc, kOwner6));
  daemon->advance_ms(100);
  int served = 0;
  for (auto& c : held)
    if (c->ask("AZ?\n").rfind("OK AZ", 0) == 0) ++served;
  const HttpResponse m = http(web, "GET", "/api/settings");
  const int cap = static_cast<int>(json_number(m.body, "net.max_per_address"));
  std::printf("[ measured ] 8 connections from [::1]: %d served in full (cap %d)\n", served, cap);
  EXPECT_GT(cap, 0);
  EXPECT_LE(served, cap);
  TcpClient other(daemon->ports().wrc, host(2));
  EXPECT_EQ(other.ask("AZ?\n").rfind("OK AZ", 0), 0u);
}

TEST_F(Ipv6, HttpStopReachesAnIpv6OwnerThroughTricklingHosts) {
  constexpr const char* kHead = "GET /api/status HTTP/1.1\r\nHost: [::1]\r\nX-Slow: ";
  std::vector<std::unique_ptr<TcpClient>> tricklers(8);
  int answered = 0;
  for (int second = 0; second < 40; ++second) {
    for (std::size_t i = 0; i < tricklers.size(); ++i) {
      if (tricklers[i] && !tricklers[i]->closed_now()) {
        tricklers[i]->send("a");
        continue;
      }
      tricklers[i] = std::make_unique<TcpClient>(web, host(2 + static_cast<int>(i)));
      tricklers[i]->send(kHead);
    }
    if (second % 2 == 1 && http_from(kOwner6, web, "POST", "/api/stop").status == 200) ++answered;
    daemon->advance_ms(1000);
  }
  std::printf("[ measured ] 8 IPv4 hosts trickling: POST /api/stop over [::1] answered %d of 20\n",
              answered);
  EXPECT_EQ(answered, 20);
}

TEST_F(Ipv6, GuessesOverIpv6SpendTheStrangersBudgetAndAListedIpv4GetsIn) {
  // The owner, 127.0.0.1, listed in IPv6 notation; [::1] guesses among IPv4 hosts.
  set(R"({"access.control_networks": "::ffff:127.0.0.1/128"})");
  ASSERT_EQ(http(web, "POST", "/api/password", R"({"password": "correct horse"})").status, 200);
  std::vector<std::string> attackers;
  for (int n = 1; n <= 16; ++n)
    attackers.push_back(n % 2 == 0 ? kOwner6 : "127.0.1." + std::to_string(n));
  int owner_in = 0;
  // A minute (the hashing of a second one would make the test slow).
  const int checked =
      guess_attack(attackers, host(1), 60, owner_in, "[::1] and 8 IPv4 hosts guessing");
  EXPECT_LE(checked, static_cast<int>(10 * minutes) + 2);  // 10 a minute, the burst of 2
  EXPECT_EQ(owner_in, 10);
  EXPECT_NE(daemon->output().find("failed web login from ::1"), std::string::npos);
}

TEST_F(Ipv6, AnOwnerListedByAnIpv6PrefixGetsInDuringAnAttack) {
  set(R"({"access.control_networks": "::1/128"})");
  ASSERT_EQ(http(web, "POST", "/api/password", R"({"password": "correct horse"})").status, 200);
  std::vector<std::string> attackers;
  for (int n = 1; n <= 16; ++n) attackers.push_back("127.0.1." + std::to_string(n));
  int owner_in = 0;
  const int checked = guess_attack(attackers, kOwner6, 120, owner_in, "16 IPv4 hosts guessing");
  EXPECT_LE(checked, static_cast<int>(10 * minutes) + 2);
  EXPECT_EQ(owner_in, 20);
}

}  // namespace
}  // namespace rotord::testing
