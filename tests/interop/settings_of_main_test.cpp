// The settings through the real daemon as main served them before the
// per-axis rows were declared once (issue 25): the schema the settings page
// is built from, every value, the help sentences, and a settings file main's
// daemon wrote with every key changed, read back as main read it. The
// captures are tests/data/settings/ (README.md there says how they were made).
#include <unistd.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "../unit/json_members.hpp"
#include "daemon_process.hpp"
#include "file_text.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

std::string main_capture(const std::string& name) {
  return read_file(std::string(ROTORD_SOURCE_DIR) + "/tests/data/settings/" + name);
}

/// The body of a GET through curl (the assets are always gzipped: --compressed).
std::string get(const std::string& address, int port, const std::string& path,
                const std::string& cookies = "") {
  const CommandOutput r = run_command("curl -sS --compressed --max-time 20 " +
                                      (cookies.empty() ? std::string() : "-b " + cookies + " ") +
                                      "http://" + address + ":" + std::to_string(port) + path);
  EXPECT_EQ(r.rc, 0) << r.out;
  return r.out;
}

// Each row, value and help sentence of main byte for byte and in main's
// order (json_members.hpp); a setting added since may sit between them.
TEST(SettingsOfMain, TheSchemaEveryValueAndTheHelpAreMainsByteForByte) {
  DaemonProcess daemon({"--sim", "g5500"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const int web = daemon.ports().web;
  // Keys, order, types, units, ranges, defaults, groups, labels, conditions.
  const std::string schema = get("127.0.0.1", web, "/api/settings/schema");
  const std::string main_schema = main_capture("main_g5500_schema.json");
  for (const char* member : {"\"platform\"", "\"groups\""})
    EXPECT_EQ(json_member_value(schema, member), json_member_value(main_schema, member)) << member;
  EXPECT_EQ(missing_or_changed(json_member_value(main_schema, "\"settings\""),
                               json_member_value(schema, "\"settings\"")),
            "");
  EXPECT_EQ(missing_or_changed(main_capture("main_g5500_api_settings.json"),
                               get("127.0.0.1", web, "/api/settings")),
            "");
  // The help sentences (web/tools/settings_help.mjs expands the per-axis rows).
  EXPECT_EQ(missing_or_changed(main_capture("main_settings_help.js"),
                               get("127.0.0.1", web, "/settings_help.js")),
            "");
}

TEST(SettingsOfMain, AFileMainWroteWithEveryKeyChangedReadsBackAsMainReadIt) {
  const std::string dir = make_temp_dir("rotord-settings-of-main");
  const std::string path = dir + "/settings.json";
  const std::string file = main_capture("main_every_key.json");
  std::ofstream(path) << file;
  run_command("chmod 600 " + path);
  // The file turns on the N1MM+ and PstRotator listeners at fixed UDP ports:
  // an address of this test's own on the loopback keeps two runs at once
  // (other worktrees, another suite) from taking each other's ports.
  const std::string address = "127.0.25." + std::to_string(20 + ::getpid() % 200);
  {
    DaemonProcess daemon({"--sim", "g5500", "--config", path, "--bind", address});
    ASSERT_TRUE(daemon.ready()) << daemon.output();
    EXPECT_NE(daemon.output().find("settings loaded from " + path), std::string::npos)
        << daemon.output();
    const int web = daemon.ports().web;
    // The file sets the web password: log in as the owner would.
    const std::string jar = dir + "/cookies";
    const CommandOutput login =
        run_command("curl -sS --max-time 20 -c " + jar +
                    " --json '{\"password\": \"fixture password 25\"}' http://" + address + ":" +
                    std::to_string(web) + "/api/login");
    ASSERT_EQ(login.out, R"({"ok":true})") << login.out;
    EXPECT_EQ(missing_or_changed(main_capture("main_every_key_api_settings.json"),
                                 get(address, web, "/api/settings", jar)),
              "");
  }
  // Read, not rewritten: the stored file is still main's, byte for byte.
  EXPECT_EQ(read_file(path), file);
  run_command("rm -rf " + dir);
}

}  // namespace
}  // namespace rotord::testing
