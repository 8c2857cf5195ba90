// The systemd unit's ExecStart line (debian/rotord.service) started the way
// systemd starts it under Type=notify and WatchdogSec=: with a NOTIFY_SOCKET
// of the test's own (a unix datagram socket), WATCHDOG_USEC and WATCHDOG_PID,
// and STATE_DIRECTORY. rotord must send READY=1 once every port listens,
// then WATCHDOG=1 again and again from its control tick, and STOPPING=1 on
// SIGTERM. The test asserts that the messages arrive, never their interval.
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"

namespace rotord::testing {
namespace {

/// The words of the unit's ExecStart= line, with $VAR expanded the way
/// systemd expands an unbraced variable: split into words.
std::vector<std::string> exec_start(const std::string& unit_path, const std::string& var,
                                    const std::vector<std::string>& value) {
  std::ifstream unit(unit_path);
  std::string line;
  while (std::getline(unit, line)) {
    if (line.rfind("ExecStart=", 0) != 0) continue;
    std::istringstream words(line.substr(10));
    std::vector<std::string> argv;
    for (std::string w; words >> w;) {
      if (w == "$" + var) {
        argv.insert(argv.end(), value.begin(), value.end());
      } else {
        argv.push_back(w);
      }
    }
    return argv;
  }
  return {};
}

class ServiceNotifyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir[] = "/tmp/rotord-notify-XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    dir_ = dir;
    socket_path_ = dir_ + "/notify";
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(fd_, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", socket_path_.c_str());
    ASSERT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    // A bound on waiting for liveness only; nothing is timed.
    timeval tv{20, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (fd_ >= 0) ::close(fd_);
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  void start(const std::vector<std::string>& argv) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const int out = ::open((dir_ + "/output").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      ::dup2(out, 1);
      ::dup2(out, 2);
      ::setenv("NOTIFY_SOCKET", socket_path_.c_str(), 1);
      ::setenv("WATCHDOG_USEC", "200000", 1);  // short, so the test sees several
      ::setenv("WATCHDOG_PID", std::to_string(::getpid()).c_str(), 1);
      ::setenv("STATE_DIRECTORY", dir_.c_str(), 1);
      ::unsetenv("JOURNAL_STREAM");
      std::vector<char*> args;
      for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      ::execv(args[0], args.data());
      ::_exit(127);
    }
  }
  /// The next datagram, or "" when none came within the liveness bound.
  std::string receive() {
    char buf[4096];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
  }
  std::string output() const {
    std::ifstream in(dir_ + "/output");
    return {std::istreambuf_iterator<char>(in), {}};
  }

  std::string dir_;
  std::string socket_path_;
  int fd_ = -1;
  pid_t pid_ = -1;
};

TEST_F(ServiceNotifyTest, TheUnitsExecStartSaysReadyThenFeedsTheWatchdogUntilStopped) {
  const int web = free_port();
  const int rotctld = free_port();
  std::vector<std::string> argv = exec_start(
      std::string(ROTORD_SOURCE_DIR) + "/debian/rotord.service", "ROTORD_OPTS",
      {"--hw", "sim", "--bind", "127.0.0.1", "--web-port", std::to_string(web), "--rotctld-port",
       std::to_string(rotctld), "--wrc-port", "0", "--gs232-port", "0", "--easycomm-port", "0"});
  ASSERT_GE(argv.size(), 2u) << "no ExecStart= in debian/rotord.service";
  ASSERT_EQ(argv[0], "/usr/bin/rotord");
  argv[0] = ROTORD_BINARY;
  start(argv);

  const std::string ready = receive();
  ASSERT_NE(ready.find("READY=1"), std::string::npos) << ready << "\n" << output();
  EXPECT_NE(ready.find("STATUS="), std::string::npos) << ready;
  // READY=1 means every port listens: both accept a connection now.
  for (const int port : {web, rotctld}) {
    TcpClient client(port);
    EXPECT_TRUE(client.connected()) << "port " << port << " not listening at READY=1";
  }
  for (int n = 0; n < 5; ++n) {
    const std::string message = receive();
    EXPECT_EQ(message, "WATCHDOG=1") << "message " << n << "\n" << output();
  }
  // The settings file is the service's: $STATE_DIRECTORY/settings.json.
  EXPECT_NE(output().find(dir_ + "/settings.json"), std::string::npos) << output();

  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  std::string message;
  for (int n = 0; n < 100; ++n) {  // watchdog messages may still be in flight
    message = receive();
    if (message != "WATCHDOG=1") break;
  }
  EXPECT_NE(message.find("STOPPING=1"), std::string::npos) << message;
  int status = 0;
  ASSERT_EQ(::waitpid(pid_, &status, 0), pid_);
  pid_ = -1;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
}

TEST_F(ServiceNotifyTest, NothingIsSentOutsideSystemd) {
  // Without NOTIFY_SOCKET rotord runs as before (DaemonProcess sets none).
  ::unsetenv("NOTIFY_SOCKET");
  DaemonProcess daemon({"--log-level", "debug"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  EXPECT_EQ(daemon.output().find("watchdog"), std::string::npos) << daemon.output();
  EXPECT_EQ(daemon.terminate(), 0);
}

}  // namespace
}  // namespace rotord::testing
