// The restarts in the command layer (core/command/system_commands.hpp,
// issue 25): REST's POST /api/reboot and the console's `reboot` are one
// command over one port interface, and write the same log line, done or
// not supported; `bootsel` writes its own. The replies stay as they were.
#include <gtest/gtest.h>

#include <string>

#include "command/command_log.hpp"
#include "command/system_commands.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "protocol/console_session.hpp"
#include "string_sink.hpp"
#include "web/http_session.hpp"

namespace rotord::command {
namespace {

using rotord::testing::LineSink;
using rotord::testing::StringSink;

const access::Peer kClient = access::Peer::from_ipv4(0xC0A8011Eu);  // 192.168.1.30

/// A port that restarts (Linux: reboot, no bootloader), counting requests.
class Port final : public SystemHooks {
 public:
  int reboots = 0;
  const char* reboot() override {
    ++reboots;
    return nullptr;
  }
  const char* reboot_to_bootloader() override { return "no USB bootloader here"; }
};

/// One rotator with its log, a REST session and a console session over the
/// same port (or none: `port` nullptr).
struct Fronts {
  explicit Fronts(SystemHooks* port) : hooks(port) {
    r.run_ms(50);
    r.controller->attach_journal(&log);
    rest.set_peer(kClient);
    console.set_peer(kClient);
  }
  std::string post_reboot() {
    StringSink sink;
    rest.receive(rotord::testing::post_request("/api/reboot", "{}"), sink);
    return sink.data;
  }
  std::string say(const std::string& line) {
    StringSink sink;
    console.receive(line + "\r\n", sink);
    return sink.data;
  }
  /// Each line with its front end's name taken out; then forgotten.
  std::vector<std::string> lines() {
    std::vector<std::string> out;
    for (std::string line : log_lines.lines) {
      for (const std::string front : {"from console", "from rest"})
        if (const std::size_t at = line.find(front); at != std::string::npos)
          line.replace(at, front.size(), "from <front>");
      out.push_back(line);
    }
    log_lines.lines.clear();
    return out;
  }

  SystemHooks* hooks;
  rotord::testing::FakeRotator r;
  LineSink log_lines;
  CommandLog log{log_lines};
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, hooks, "1"}};
  web::HttpSession rest{api};
  protocol::ConsolePort console_port{nullptr, nullptr, hooks, "test"};
  protocol::ConsoleSession console{*r.controller, "1", &console_port};
};

TEST(SystemCommands, RestAndTheConsoleWriteTheSameLineForAReboot) {
  Port port;
  Fronts f(&port);
  const std::string rest = f.post_reboot();
  EXPECT_NE(rest.find("HTTP/1.1 202 "), std::string::npos) << rest;
  EXPECT_NE(rest.find("\r\n\r\n{\"ok\":true,\"rebooting\":true}"), std::string::npos) << rest;
  EXPECT_TRUE(f.rest.wants_close());
  const std::vector<std::string> rest_lines = f.lines();
  EXPECT_EQ(f.say("reboot"), "ok rebooting\r\n");
  EXPECT_EQ(port.reboots, 2);  // both through the one port interface
  const std::vector<std::string> want = {"command reboot from <front> (192.168.1.30): OK"};
  EXPECT_EQ(rest_lines, want);
  EXPECT_EQ(f.lines(), want);
}

TEST(SystemCommands, APortThatCannotRestartWritesNotSupportedFromBoth) {
  Fronts f(nullptr);
  const std::string rest = f.post_reboot();
  EXPECT_NE(rest.find("HTTP/1.1 501 "), std::string::npos) << rest;
  EXPECT_NE(rest.find("{\"error\":\"this port cannot restart the controller\"}"), std::string::npos)
      << rest;
  EXPECT_FALSE(f.rest.wants_close());
  const std::vector<std::string> rest_lines = f.lines();
  EXPECT_EQ(f.say("reboot"), "error: reboot is not available on this port\r\n");
  const std::vector<std::string> want = {
      "command reboot from <front> (192.168.1.30): NOT SUPPORTED"};
  EXPECT_EQ(rest_lines, want);
  EXPECT_EQ(f.lines(), want);
}

TEST(SystemCommands, BootselWritesItsOwnLineDoneOrNot) {
  Port port;  // Linux: no bootloader
  Fronts linux_like(&port);
  EXPECT_EQ(linux_like.say("bootsel"), "error: no USB bootloader here\r\n");
  EXPECT_EQ(linux_like.lines(),
            std::vector<std::string>{"command bootsel from <front> (192.168.1.30): NOT SUPPORTED"});
  EXPECT_EQ(port.reboots, 0);

  struct Pico final : SystemHooks {
    bool bootloader = false;
    const char* reboot() override { return nullptr; }
    const char* reboot_to_bootloader() override {
      bootloader = true;
      return nullptr;
    }
  } pico;
  Fronts pico_like(&pico);
  EXPECT_EQ(pico_like.say("bootsel"),
            "ok rebooting into the USB bootloader: copy the .uf2 onto the RPI-RP2 drive\r\n");
  EXPECT_TRUE(pico.bootloader);
  EXPECT_EQ(pico_like.lines(),
            std::vector<std::string>{"command bootsel from <front> (192.168.1.30): OK"});
}

}  // namespace
}  // namespace rotord::command
