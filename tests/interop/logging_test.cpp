// rotord's log options (issue 12): --log-level filters, --log-format json
// writes one JSON object per line, on the real daemon. Checked with
// nlohmann-json (Debian nlohmann-json3-dev), a parser rotord does not use.
#include <gtest/gtest.h>
#include <signal.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

/// rotord refusing an invalid --bind: a few info lines, then one error.
CommandOutput refused_start(const std::string& log_options) {
  const std::string dir = make_temp_dir("rotord-log");
  CommandOutput r = run_command("timeout 20 " ROTORD_BINARY " --config " + dir +
                                "/settings.json --bind nonsense --web-port 0 " + log_options);
  run_command("rm -rf " + dir);
  return r;
}

TEST(Logging, TextLinesByDefault) {
  const CommandOutput r = refused_start("");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.out.find("rotord: no settings file at "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rotord: invalid bind address 'nonsense'"), std::string::npos) << r.out;
}

TEST(Logging, LogLevelErrorKeepsOnlyErrors) {
  const CommandOutput r = refused_start("--log-level error");
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.out, "rotord: invalid bind address 'nonsense'\n");
  const CommandOutput warn = refused_start("--log-level warn");
  EXPECT_EQ(warn.out, "rotord: invalid bind address 'nonsense'\n");
}

TEST(Logging, AnUnknownLevelOrFormatIsRefused) {
  EXPECT_NE(refused_start("--log-level verbose").rc, 0);
  EXPECT_NE(refused_start("--log-format xml").rc, 0);
}

TEST(Logging, JsonIsOneObjectPerLineWithTimeLevelAndMessage) {
  const CommandOutput r = refused_start("--log-format json");
  EXPECT_EQ(r.rc, 2);
  const auto lines = lines_of(r.out);
  ASSERT_GE(lines.size(), 3u) << r.out;
  for (const std::string& line : lines) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    ASSERT_TRUE(j.is_object()) << line;
    ASSERT_TRUE(j["time"].is_string()) << line;
    // RFC 3339 UTC with milliseconds: 2026-11-24T10:15:00.123Z
    EXPECT_EQ(j["time"].get<std::string>().size(), 24u) << line;
    EXPECT_EQ(j["time"].get<std::string>().back(), 'Z') << line;
    ASSERT_TRUE(j["level"].is_string()) << line;
    ASSERT_TRUE(j["msg"].is_string()) << line;
    EXPECT_EQ(line.find("rotord: "), std::string::npos) << line;
  }
  const auto last = nlohmann::json::parse(lines.back(), nullptr, false);
  EXPECT_EQ(last["level"], "error");
  EXPECT_EQ(last["msg"], "invalid bind address 'nonsense'");
}

TEST(Logging, AJsonDaemonLogsItsWholeLifeAsJson) {
  DaemonProcess daemon({"--clock", "manual", "--log-format", "json", "--log-level", "debug"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  {
    TcpClient wrc(daemon.ports().wrc);
    ASSERT_EQ(wrc.ask("AZ 300\n"), "OK AZ 300.00");
    ASSERT_TRUE(daemon.wait_for_output("connected\"}")) << daemon.output();
  }
  ASSERT_TRUE(daemon.wait_for_output("disconnected\"}")) << daemon.output();
  EXPECT_EQ(daemon.stop_with(SIGTERM), 0);
  bool saw_ready = false, saw_debug = false, saw_stop = false;
  for (const std::string& line : lines_of(daemon.output())) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    ASSERT_TRUE(j.is_object()) << line;
    const std::string msg = j.value("msg", "");
    saw_ready |= msg == "ready";
    saw_debug |=
        j.value("level", "") == "debug" && msg.rfind("WRC text protocol: 127.0.0.1:", 0) == 0;
    saw_stop |= msg == "stopped; outputs at the driver: az off, el off";
  }
  EXPECT_TRUE(saw_ready && saw_debug && saw_stop) << daemon.output();
}

TEST(Logging, ConnectionsAreLoggedOnlyAtDebug) {
  DaemonProcess daemon({"--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  {
    TcpClient wrc(daemon.ports().wrc);
    ASSERT_EQ(wrc.ask("AZ?\n").substr(0, 5), "OK AZ");
  }
  EXPECT_EQ(daemon.stop_with(SIGTERM), 0);
  EXPECT_EQ(daemon.output().find("connected"), std::string::npos) << daemon.output();
}

}  // namespace
}  // namespace rotord::testing
