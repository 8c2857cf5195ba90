// rotctld details found by testing rotord from outside (issue 23): \pause on a
// fresh connection, Hamlib clients before 4.5.1 reading \dump_state by line
// position, \dump_conf as Hamlib 4.6's rotctld answers it. Each through the
// real daemon on a real socket.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

using Clock = std::chrono::steady_clock;

long long ms_since(Clock::time_point start) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start).count();
}

TEST(RotctldClients, PauseOnAFreshConnectionWaitsItsSeconds) {
  // Seen on main: the first \pause of a connection took its deadline from a
  // transport time not yet read (0), so after a few seconds of uptime it
  // answered at once. Only a lower bound is checked: load can make the reply
  // late, never early.
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  // The daemon's network clock must run past the pause's length before the
  // connection opens: the manual clock moves it 3 s at once. The pause
  // itself then runs on the wall clock (nothing advances it below).
  ASSERT_GE(daemon.advance_ms(3000), 3000);
  for (int seconds : {1, 2}) {
    TcpClient rotctld(daemon.ports().rotctld);
    const Clock::time_point sent = Clock::now();
    ASSERT_TRUE(rotctld.send("\\pause " + std::to_string(seconds) + "\n"));
    std::string line;
    ASSERT_TRUE(rotctld.read_line(line, 20000));  // liveness bound only
    const long long waited_ms = ms_since(sent);
    std::printf("fresh connection: \\pause %d answered after %lld ms\n", seconds, waited_ms);
    EXPECT_EQ(line, "RPRT 0");
    EXPECT_GE(waited_ms, seconds * 1000LL);
  }
}

/// A client socket read the way Hamlib 4.4's iofunc.c read_string() and
/// network.c network_flush() read it: one byte at a time up to the LF, and
/// whatever is waiting (FIONREAD) thrown away before each command.
class Hamlib44Port {
 public:
  explicit Hamlib44Port(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~Hamlib44Port() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool ok() const { return fd_ >= 0; }

  /// read_string(port, buf, BUF_MAX = 64, "\n", ...): at most 63 bytes, the
  /// LF kept; < 0 on timeout (Hamlib's rotator timeout; liveness here).
  int read_string(char (&buf)[64]) {
    std::memset(buf, 0, sizeof(buf));
    int total = 0;
    while (total < 63) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 5000) <= 0) return total == 0 ? -5 : total;  // -RIG_ETIMEOUT
      char c = 0;
      if (::recv(fd_, &c, 1, 0) != 1) return -6;  // -RIG_EIO
      buf[total++] = c;
      if (c == '\n') break;
    }
    return total;
  }

  /// network_flush(): drains what has already arrived, without waiting.
  void flush() {
    for (;;) {
      int len = 0;
      if (::ioctl(fd_, FIONREAD, &len) != 0 || len <= 0) return;
      char drop[1024];
      if (::recv(fd_, drop, static_cast<std::size_t>(len) < sizeof(drop) ? len : sizeof(drop), 0) <=
          0)
        return;
    }
  }

  /// netrotctl_transaction(): flush, write, read one line; "RPRT n" gives n.
  int transaction(const char* cmd, char (&buf)[64]) {
    flush();
    const std::size_t len = std::strlen(cmd);
    if (::send(fd_, cmd, len, MSG_NOSIGNAL) != static_cast<ssize_t>(len)) return -6;
    const int ret = read_string(buf);
    if (ret < 0) return ret;
    if (std::memcmp(buf, "RPRT ", 5) == 0) return std::atoi(buf + 5);
    return ret;
  }

 private:
  int fd_ = -1;
};

/// Hamlib 4.4's rigs/dummy/netrotctl.c as a client: netrotctl_open() reads
/// \dump_state by line position, rot_set_position() (src/rotator.c) refuses
/// a position outside those limits before anything is sent.
struct Hamlib44Client {
  explicit Hamlib44Client(int tcp_port) : port(tcp_port) {}

  /// netrotctl_open(): 0 (RIG_OK) or a negative Hamlib error.
  int open() {
    char buf[64];
    int ret = port.transaction("\\dump_state\n", buf);
    if (ret <= 0) return ret < 0 ? ret : -8;  // -RIG_EPROTO
    const int prot_ver = std::atoi(buf);
    if (prot_ver < 0) return -8;  // ROTCTLD_PROT_VER 0
    ret = port.read_string(buf);  // the rotator model, dropped
    if (ret <= 0) return ret < 0 ? ret : -8;
    double* limits[] = {&min_az, &max_az, &min_el, &max_el};
    for (double* limit : limits) {
      ret = port.read_string(buf);
      if (ret <= 0) return ret < 0 ? ret : -8;
      *limit = std::atof(buf);
    }
    return 0;
  }

  /// rot_set_position() then netrotctl_set_position().
  int set_position(float az, float el) {
    if (az < min_az || az > max_az || el < min_el || el > max_el) return -1;  // -RIG_EINVAL
    char cmd[32];
    std::snprintf(cmd, sizeof(cmd), "P %f %f\n", static_cast<double>(az), static_cast<double>(el));
    char buf[64];
    const int ret = port.transaction(cmd, buf);
    return ret > 0 ? -8 : ret;
  }

  /// netrotctl_get_position().
  int get_position(double& az, double& el) {
    char buf[64];
    int ret = port.transaction("p\n", buf);
    if (ret <= 0) return ret < 0 ? ret : -8;
    az = std::atof(buf);
    ret = port.read_string(buf);
    if (ret <= 0) return ret < 0 ? ret : -8;
    el = std::atof(buf);
    return 0;
  }

  Hamlib44Port port;
  double min_az = 0, max_az = 0, min_el = 0, max_el = 0;
};

TEST(RotctldClients, HamlibBefore451ReadsTheLimitsWithRotctldOldClients) {
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  {
    // The default is byte-equal to Hamlib 4.5.4's rotctld, which such a
    // client reads as limits 0..0 (Hamlib issue 1660).
    Hamlib44Client old(daemon.ports().rotctld);
    ASSERT_TRUE(old.port.ok());
    ASSERT_EQ(old.open(), 0);
    std::printf("Hamlib 4.4 parse, default: az %g..%g el %g..%g\n", old.min_az, old.max_az,
                old.min_el, old.max_el);
    EXPECT_EQ(old.max_az, 0.0);
    EXPECT_EQ(old.set_position(200, 30), -1);
  }
  // The user turns the setting on (web settings page, REST).
  ASSERT_EQ(
      http(daemon.ports().web, "POST", "/api/settings", R"({"rotctld.old_clients": true})").status,
      200);
  Hamlib44Client old(daemon.ports().rotctld);
  ASSERT_TRUE(old.port.ok());
  ASSERT_EQ(old.open(), 0);
  std::printf("Hamlib 4.4 parse, rotctld.old_clients: az %g..%g el %g..%g\n", old.min_az,
              old.max_az, old.min_el, old.max_el);
  EXPECT_EQ(old.min_az, 0.0);
  EXPECT_EQ(old.max_az, 450.0);
  EXPECT_EQ(old.min_el, 0.0);
  EXPECT_EQ(old.max_el, 180.0);
  // The tagged lines it left unread are flushed before its next command, so
  // every later reply is read in step.
  EXPECT_EQ(old.set_position(200, 30), 0);
  double az = -1, el = -1;
  EXPECT_EQ(old.get_position(az, el), 0);
  EXPECT_GE(az, 0.0);
  EXPECT_LE(az, 450.0);
  EXPECT_EQ(old.set_position(400, 170), 0);
  EXPECT_EQ(old.set_position(451, 10), -1);  // refused by the client itself

  // Hamlib 4.5.4's own client still reads the tagged limits: 400 is beyond
  // netrotctl's built-in 180 and is accepted only from \dump_state.
  const std::string where = "127.0.0.1:" + std::to_string(daemon.ports().rotctld);
  const CommandOutput newer = run_command("timeout 20 rotctl -m 2 -r " + where + " P 400 30");
  EXPECT_EQ(newer.rc, 0) << newer.out;
}

TEST(RotctldClients, DumpConfIsAnsweredAsHamlib46sRotctldAnswersIt) {
  // Seen on main: RPRT -4. Hamlib 4.6's rotctld prints the list on its own
  // standard output and answers the client RPRT 0.
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  TcpClient rotctld(daemon.ports().rotctld);
  EXPECT_EQ(rotctld.ask("\\dump_conf\n"), "RPRT 0");
  EXPECT_EQ(rotctld.ask("3\n"), "RPRT 0");
  EXPECT_EQ(rotctld.ask("+\\dump_conf\n"), "dump_conf:");
  std::string line;
  ASSERT_TRUE(rotctld.read_line(line));
  EXPECT_EQ(line, "RPRT 0");
}

TEST(RotctldClients, NumbersAreReadWholeOrRefusedAndNothingMoves) {
  // Issue 29 item 7, seen on main: \pause 1e9 paused 1 s, 60.5 and 3abc
  // paused 60 and 3 s, M 16 1e400 moved at speed 1, Easycomm VU999 and VD-0
  // moved the elevation.
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  TcpClient rotctld(daemon.ports().rotctld);
  for (const char* bad : {"\\pause 1e9\n", "\\pause 60.5\n", "\\pause 3abc\n", "M 16 1e400\n",
                          "M 2 50.5\n", "V SPEED 3abc\n"})
    EXPECT_EQ(rotctld.ask(bad), "RPRT -1") << bad;
  TcpClient easycomm(daemon.ports().easycomm);
  for (const char* bad : {"VU999\n", "VD-0\n", "VL+100\n"})
    EXPECT_EQ(easycomm.ask(bad), "ALSYNTAX") << bad;
  daemon.advance_ms(2000);
  const std::string status = http(daemon.ports().web, "GET", "/api/status").body;
  EXPECT_NE(status.find("\"moving\":false"), std::string::npos) << status;
  // What Hamlib's 204 sends still moves: "VU%04d".
  ASSERT_TRUE(easycomm.send("VU0100\n"));
  daemon.advance_ms(1000);
  const std::string moving = http(daemon.ports().web, "GET", "/api/status").body;
  EXPECT_NE(moving.find("\"moving\":true"), std::string::npos) << moving;
  EXPECT_EQ(rotctld.ask("S\n"), "RPRT 0");
}

}  // namespace
}  // namespace rotord::testing
