// The settings file through the real daemon (issue 10 items 6 and 7): a
// FIFO as --config is refused at once, and the file keeps only the user's
// changes, so switching --sim keeps each profile's geometry.
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class SettingsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir[] = "/tmp/rotord-settings-XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    dir_ = dir;
    path_ = dir_ + "/settings.json";
  }
  void TearDown() override { run_command("rm -rf " + dir_); }

  std::string read_file() const {
    std::ifstream in(path_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  void write_file(const std::string& text) const { std::ofstream(path_) << text; }

  std::string dir_;
  std::string path_;
};

TEST_F(SettingsFile, AFifoAsConfigIsRefusedWithExitStatusTwo) {
  ASSERT_EQ(::mkfifo(path_.c_str(), 0600), 0);
  // `timeout` bounds the old hang; the refusal comes long before it.
  const CommandOutput r = run_command("timeout 20 " + std::string(ROTORD_BINARY) +
                                      " --web-port 0 --wrc-port 0 --rotctld-port 0 --gs232-port 0"
                                      " --easycomm-port 0 --seed-port 0 --config " +
                                      path_ + " 2>&1");
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("is a FIFO, not a regular file"), std::string::npos) << r.out;
}

TEST_F(SettingsFile, SwitchingTheSimulatorKeepsEachProfilesGeometryAndTheUsersChanges) {
  {
    DaemonProcess ham4({"--sim", "ham4", "--config", path_});
    ASSERT_TRUE(ham4.ready()) << ham4.output();
    const HttpResponse r =
        http(ham4.ports().web, "POST", "/api/settings", R"({"park.az_deg": 123})");
    ASSERT_EQ(r.status, 200) << r.body;
  }
  const std::string stored = read_file();
  EXPECT_NE(stored.find("\"settings_version\": 2"), std::string::npos) << stored;
  EXPECT_NE(stored.find("\"park.az_deg\": 123"), std::string::npos) << stored;
  EXPECT_EQ(stored.find("az.max_deg"), std::string::npos) << stored;
  EXPECT_EQ(stored.find("el.enabled"), std::string::npos) << stored;
  struct stat st {};
  ASSERT_EQ(::stat(path_.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);  // it may hold the Wi-Fi password

  DaemonProcess g5500({"--sim", "g5500", "--config", path_});
  ASSERT_TRUE(g5500.ready()) << g5500.output();
  const HttpResponse s = http(g5500.ports().web, "GET", "/api/settings");
  EXPECT_EQ(json_number(s.body, "az.max_deg"), 450.0) << s.body;
  EXPECT_NE(s.body.find("\"el.enabled\":true"), std::string::npos) << s.body;
  EXPECT_EQ(json_number(s.body, "park.az_deg"), 123.0) << s.body;
}

TEST_F(SettingsFile, AnExportImportedBackChangesNothing) {
  DaemonProcess daemon({"--sim", "spid", "--config", path_});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  ASSERT_EQ(http(daemon.ports().web, "POST", "/api/settings", R"({"park.az_deg": 10})").status,
            200);
  const std::string stored = read_file();
  const HttpResponse exported = http(daemon.ports().web, "GET", "/api/settings");
  ASSERT_EQ(exported.status, 200);
  const HttpResponse imported = http(daemon.ports().web, "POST", "/api/settings", exported.body);
  EXPECT_EQ(imported.status, 200) << imported.body;
  EXPECT_EQ(read_file(), stored);
}

TEST_F(SettingsFile, AFileWithEverySettingFromAnotherProfileIsMigratedWithoutLosingAChange) {
  // What a rotord before layering stored under --sim ham4: every setting,
  // the export of the same daemon.
  std::string legacy;
  {
    DaemonProcess ham4({"--sim", "ham4", "--config", dir_ + "/other.json"});
    ASSERT_TRUE(ham4.ready()) << ham4.output();
    ASSERT_EQ(http(ham4.ports().web, "POST", "/api/settings", R"({"park.az_deg": 77})").status,
              200);
    legacy = http(ham4.ports().web, "GET", "/api/settings").body;
  }
  ASSERT_NE(legacy.find("\"az.max_deg\":360"), std::string::npos) << legacy;
  write_file(legacy);

  DaemonProcess g5500({"--sim", "g5500", "--config", path_});
  ASSERT_TRUE(g5500.ready()) << g5500.output();
  EXPECT_NE(g5500.output().find("over the simulator profile ham4"), std::string::npos)
      << g5500.output();
  const HttpResponse s = http(g5500.ports().web, "GET", "/api/settings");
  EXPECT_EQ(json_number(s.body, "az.max_deg"), 450.0) << s.body;
  EXPECT_NE(s.body.find("\"el.enabled\":true"), std::string::npos) << s.body;
  EXPECT_EQ(json_number(s.body, "park.az_deg"), 77.0) << s.body;
}

}  // namespace
}  // namespace rotord::testing
