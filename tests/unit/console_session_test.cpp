#include "protocol/console_session.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_rotator.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;
using testing::StringSink;

class RecordingHooks final : public command::SystemHooks {
 public:
  int reboots = 0;
  int bootloader = 0;
  const char* refuse = nullptr;
  const char* reboot() override {
    if (refuse != nullptr) return refuse;
    ++reboots;
    return nullptr;
  }
  const char* reboot_to_bootloader() override {
    if (refuse != nullptr) return refuse;
    ++bootloader;
    return nullptr;
  }
};

class ConsoleTest : public ::testing::Test {
 protected:
  ConsoleTest() {
    r.run_ms(50);
    session.set_peer(access::Peer::line());
  }
  testing::FakeRotator r;
  settings::Settings defaults = r.settings;  // the board's defaults: as the rotator started
  settings::Settings scratch;
  RecordingHooks hooks;
  ConsolePort port{&defaults, &scratch, &hooks, "test board"};
  ConsoleSession session{*r.controller, "9.9.9", &port};

  /// Sends bytes and returns every byte written, the listing included (as a
  /// transport without a bound does: drain_output).
  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    drain_output(session, sink);
    return sink.data;
  }
  settings::Settings& values() { return r.controller->settings(); }
  /// The last line of a reply (without its CR LF).
  static std::string last_line(const std::string& reply) {
    std::string s = reply;
    if (s.size() >= 2 && s.compare(s.size() - 2, 2, "\r\n") == 0) s.resize(s.size() - 2);
    const std::size_t nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
  }
};

TEST_F(ConsoleTest, HelpListsEveryCommandThenOk) {
  const std::string reply = ask("help\r\n");
  for (const auto& c : ConsoleSession::commands())
    EXPECT_NE(reply.find(std::string(c.usage)), std::string::npos) << c.name;
  EXPECT_EQ(last_line(reply), "ok");
  EXPECT_EQ(ask("HELP\n"), reply);  // command words in any case
}

TEST_F(ConsoleTest, StatusShowsEachAxis) {
  const std::string reply = ask("status\n");
  EXPECT_NE(reply.find("rotord 9.9.9 (test board)\r\n"), std::string::npos) << reply;
  EXPECT_NE(reply.find("az position_deg=100.0 valid=1 raw=1000"), std::string::npos) << reply;
  EXPECT_NE(reply.find("\r\nel position_deg=20.0"), std::string::npos) << reply;
  EXPECT_NE(reply.find("control=yes"), std::string::npos) << reply;
  EXPECT_EQ(last_line(reply), "ok");
}

TEST_F(ConsoleTest, GetAndSetUseTheSettingsRules) {
  EXPECT_EQ(ask("get az.max_deg\n"), "ok az.max_deg=450\r\n");
  EXPECT_EQ(ask("set az.max_deg 400\n"), "ok az.max_deg=400\r\n");
  EXPECT_EQ(values().get(Id::kAzMaxDeg), 400);
  EXPECT_EQ(ask("set az.max_deg 9999\n"), "error: az.max_deg: outside the allowed range\r\n");
  // A cross-setting rule: the minimum must stay below the maximum.
  EXPECT_EQ(ask("set az.min_deg 420\n").rfind("error: ", 0), 0u);
  EXPECT_EQ(values().get(Id::kAzMinDeg), 0);
  EXPECT_EQ(ask("set az.max_deg banana\n").rfind("error: az.max_deg: ", 0), 0u);
  EXPECT_EQ(ask("set nosuch.key 1\n"),
            "error: unknown setting 'nosuch.key' (list shows every setting)\r\n");
  EXPECT_EQ(ask("get nosuch.key\n"),
            "error: unknown setting 'nosuch.key' (list shows every setting)\r\n");
  EXPECT_EQ(ask("get\n"), "error: usage: get <key> (list shows every setting)\r\n");
  EXPECT_EQ(ask("set az.max_deg\n"),
            "error: usage: set <key> <value> (\"\" for an empty text)\r\n");
  EXPECT_EQ(ask("set usb.personality console\n"),
            "ok usb.personality=console (takes effect after a reboot)\r\n");
}

TEST_F(ConsoleTest, TextValuesKeepTheirSpacesAndEmptyIsTwoQuotes) {
  EXPECT_EQ(ask("set wifi.ssid My Shack Net\n"),
            "ok wifi.ssid=My Shack Net (takes effect after a reboot)\r\n");
  EXPECT_EQ(values().text(Id::kWifiSsid), "My Shack Net");
  EXPECT_EQ(ask("set wifi.ssid \"\"\n"), "ok wifi.ssid= (takes effect after a reboot)\r\n");
  EXPECT_EQ(values().text(Id::kWifiSsid), "");
}

TEST_F(ConsoleTest, PasswordsOnlyFromALocalLineAndNeverShown) {
  EXPECT_EQ(ask("set wifi.password secret-passphrase\n"),
            "ok wifi.password=******** (takes effect after a reboot)\r\n");
  EXPECT_EQ(values().text(Id::kWifiPassword), "secret-passphrase");
  EXPECT_EQ(ask("get wifi.password\n"), "ok wifi.password=********\r\n");
  session.set_peer(access::Peer::from_ipv4(0x7F000001));
  EXPECT_EQ(ask("set wifi.password another-one\n"),
            "error: wifi.password is a password: set it over USB or serial, not the network\r\n");
  EXPECT_EQ(values().text(Id::kWifiPassword), "secret-passphrase");
}

TEST_F(ConsoleTest, WebOnlySettingsAreRefused) {
  EXPECT_EQ(ask("set access.serial_control false\n"),
            "error: access.serial_control is set through the web only\r\n");
  EXPECT_EQ(ask("set web.password x\n"), "error: web.password is set through the web only\r\n");
  EXPECT_TRUE(values().b(Id::kAccessLineControl));
}

TEST_F(ConsoleTest, AReadOnlyLineMayReadAndStopButNotChange) {
  values().set(Id::kAccessLineControl, 0);
  const std::string refused = ask("set az.max_deg 400\n");
  EXPECT_EQ(refused.rfind("error: read-only", 0), 0u) << refused;
  EXPECT_EQ(values().get(Id::kAzMaxDeg), 450);
  EXPECT_EQ(ask("reset\n"), refused);
  EXPECT_EQ(ask("reboot\n"), refused);
  EXPECT_EQ(ask("bootsel\n"), refused);
  EXPECT_EQ(ask("import {\"park.az_deg\": 90}\n"), refused);
  EXPECT_EQ(ask("cal az lo\n"), refused);
  EXPECT_EQ(hooks.reboots + hooks.bootloader, 0);
  EXPECT_EQ(ask("get az.max_deg\n"), "ok az.max_deg=450\r\n");
  EXPECT_EQ(ask("stop\n"), "ok stopped\r\n");
  EXPECT_NE(ask("status\n").find("control=no"), std::string::npos);
}

TEST_F(ConsoleTest, ResetClearsALatchedStall) {
  // Driving with the pot frozen: the stall rule latches a fault.
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  r.run_ms(6000);
  ASSERT_EQ(r.controller->status().az.fault, AxisFault::kStall);
  EXPECT_NE(ask("status\n").find("fault=STALL"), std::string::npos);
  EXPECT_EQ(ask("reset\n"), "ok stopped, faults cleared\r\n");
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
}

TEST_F(ConsoleTest, RebootAndBootselGoThroughThePortsHooks) {
  EXPECT_EQ(ask("reboot\n"), "ok rebooting\r\n");
  EXPECT_EQ(hooks.reboots, 1);
  EXPECT_EQ(ask("bootsel\n"),
            "ok rebooting into the USB bootloader: copy the .uf2 onto the RPI-RP2 drive\r\n");
  EXPECT_EQ(hooks.bootloader, 1);
  hooks.refuse = "not here";
  EXPECT_EQ(ask("bootsel\n"), "error: not here\r\n");
  ConsoleSession bare(*r.controller, "9.9.9", nullptr);
  StringSink sink;
  bare.receive("reboot\nbootsel\nexport\nimport {}\n", sink);
  EXPECT_EQ(sink.data,
            "error: reboot is not available on this port\r\n"
            "error: bootsel is not available on this port\r\n"
            "error: export is not available on this port\r\n"
            "error: import is not available on this port\r\n");
}

TEST_F(ConsoleTest, ExportIsTheChangesAsOneJsonLineAndImportsBack) {
  ask("set az.max_deg 400\nset park.az_deg 90\nset wifi.password secret-passphrase\n");
  const std::string reply = ask("export\n");
  EXPECT_EQ(reply,
            "{\"settings_version\":2,\"park.az_deg\":90,\"az.max_deg\":400}\r\n"
            "ok 2 settings differ from the defaults\r\n");
  // Onto another controller with the same defaults: the same settings.
  testing::FakeRotator other;
  ConsoleSession other_session(*other.controller, "9.9.9", &port);
  other_session.set_peer(access::Peer::line());
  StringSink sink;
  const std::string json = reply.substr(0, reply.find("\r\n"));
  other_session.receive("import " + json + "\n", sink);
  EXPECT_EQ(sink.data, "ok 2 settings changed\r\n");
  EXPECT_EQ(other.controller->settings().get(Id::kAzMaxDeg), 400);
  EXPECT_EQ(other.controller->settings().get(Id::kParkAzDeg), 90);
}

TEST_F(ConsoleTest, ImportIsAllOrNothing) {
  const std::string bad = ask("import {\"park.az_deg\": 90, \"az.max_deg\": 9999}\n");
  EXPECT_EQ(last_line(bad).rfind("error: nothing changed", 0), 0u) << bad;
  EXPECT_NE(bad.find("  az.max_deg: "), std::string::npos) << bad;
  EXPECT_EQ(values().get(Id::kParkAzDeg), 0);
  EXPECT_EQ(ask("import {\"park.az_deg\": 90, \"access.serial_control\": false}\n"),
            "error: access.serial_control cannot be imported here (web only, or a password over "
            "the network): remove it\r\n");
  EXPECT_EQ(values().get(Id::kParkAzDeg), 0);
  EXPECT_EQ(ask("import {\"park.az_deg\": \n").rfind("error: invalid JSON: ", 0), 0u);
  EXPECT_EQ(ask("import\n"), "error: usage: import {\"key\": value, ...}\r\n");
  EXPECT_EQ(ask("import {\"usb.personality\": \"seed\"}\n"),
            "ok 1 settings changed (some take effect after a reboot)\r\n");
}

TEST_F(ConsoleTest, CalibrateTakesThePresentReading) {
  r.az.adc.counts = 300;
  r.run_ms(500);
  EXPECT_EQ(ask("cal az lo\n"), "ok az lo point set from the sensor's present reading\r\n");
  EXPECT_EQ(values().get(Id::kAzPotCalLoCounts), 300);
  EXPECT_EQ(values().get(Id::kAzPotCalLoDeg), 0);  // az.min_deg
  EXPECT_EQ(ask("cal az middle\n"), "error: usage: cal <az|el> <lo|hi>\r\n");
  EXPECT_EQ(ask("cal\n"), "error: usage: cal <az|el> <lo|hi>\r\n");
}

TEST_F(ConsoleTest, ListShowsSettingsByPrefixWithoutHiddenOnes) {
  const std::string reply = ask("list park.\n");
  EXPECT_EQ(reply, "park.az_deg=0\r\npark.el_deg=0\r\npark.after_idle_min=0\r\nok 3 settings\r\n");
  const std::string all = ask("list\n");
  EXPECT_EQ(all.find("web.token_1"), std::string::npos);
  EXPECT_NE(all.find("wifi.password="), std::string::npos);
  EXPECT_EQ(ask("list zz\n"), "error: no setting starts with 'zz'\r\n");
}

TEST_F(ConsoleTest, GarbageAndLongLinesGetErrorsAndMoveNothing) {
  EXPECT_EQ(ask("\x01\x02\xff\x7f go\n"),
            "error: unknown command '\?\?\?\?' (help lists the commands)\r\n");
  EXPECT_EQ(ask(std::string(600, 'x') + "\nget az.max_deg\n"),
            "error: line too long (at most 512 bytes)\r\nok az.max_deg=450\r\n");
  // A megabyte without a line end costs no memory and answers once.
  std::string flood(1 << 20, 'A');
  EXPECT_EQ(ask(flood), "");
  EXPECT_EQ(ask("\n"), "error: line too long (at most 512 bytes)\r\n");
  EXPECT_EQ(ask("\r\n\r\n   \n"), "");  // empty lines: no reply
  r.run_ms(1000);
  EXPECT_FALSE(r.az.drive.last.any_on());
  EXPECT_FALSE(r.el.drive.last.any_on());
}

/// A transport with a bounded buffer (the Pico's USB): the listing goes out
/// in windows of the room given, whole lines each, and equals the unbounded one.
TEST_F(ConsoleTest, AListingGoesOutInWindowsOfTheRoomGiven) {
  const std::string whole = ask("list\n");
  StringSink sink;
  session.receive("list\nget az.max_deg\n", sink);
  ASSERT_TRUE(session.output_pending());
  EXPECT_EQ(sink.data, "");  // nothing until the transport says how much room it has
  int windows = 0;
  while (session.output_pending() && windows < 1000) {
    const std::size_t before = sink.data.size();
    session.write_more(200, sink);
    const std::string window = sink.data.substr(before);
    EXPECT_LE(window.size(), 200u);
    // Whole lines: a window ends with a line end (the get's reply follows the last).
    EXPECT_EQ(window.back(), '\n') << window;
    ++windows;
  }
  EXPECT_GT(windows, 10);
  // The get typed during the listing is answered after it, in order.
  EXPECT_EQ(sink.data, whole + "ok az.max_deg=450\r\n");
}

TEST_F(ConsoleTest, AListingCutShortWhenTheSettingsChange) {
  StringSink sink;
  session.receive("list\n", sink);
  session.write_more(100, sink);
  values().set(Id::kParkAzDeg, 10);
  session.write_more(100, sink);
  EXPECT_FALSE(session.output_pending());
  EXPECT_EQ(last_line(sink.data), "error: the settings changed during the listing: ask again");
}

TEST_F(ConsoleTest, InputBeyondTheHoldDuringAListingIsReported) {
  StringSink sink;
  session.receive("list\n" + std::string(ConsoleSession::kHoldBytes + 10, ' '), sink);
  drain_output(session, sink);
  EXPECT_NE(sink.data.find("error: 10 bytes typed during the listing were dropped\r\n"),
            std::string::npos);
}

TEST_F(ConsoleTest, SetupModelFillsThePublishedFiguresAndSaysWhereFrom) {
  const std::string models = ask("setup models\n");
  EXPECT_NE(models.find("hygain-ham4      Hy-Gain HAM IV\r\n"), std::string::npos) << models;
  EXPECT_EQ(last_line(models), "ok");
  values().set(Id::kAzSpeedDegS, 4.5);
  const std::string reply = ask("setup model hygain-ham4\n");
  EXPECT_NE(reply.find("az.max_deg=360 [HG3] 360 deg\r\n"), std::string::npos) << reply;
  EXPECT_NE(reply.find("az.speed_deg_s=4.5 (not published: kept"), std::string::npos) << reply;
  EXPECT_EQ(last_line(reply).rfind("ok Hy-Gain HAM IV: 6 settings filled", 0), 0u) << reply;
  EXPECT_EQ(values().get(Id::kAzMaxDeg), 360);
  EXPECT_TRUE(values().b(Id::kAzHasBrake));
  EXPECT_EQ(ask("setup model g5500\n"), "error: unknown model (setup models lists them)\r\n");
  EXPECT_EQ(
      ask("setup\n"),
      "error: usage: setup models | setup model <id> | setup station <locator or lat lon>\r\n");
}

// Issue 24: a locator typed where a position is asked for is understood.
TEST_F(ConsoleTest, SetupStationTakesALocatorOrALatitudeAndLongitude) {
  EXPECT_EQ(ask("setup station jo62qm\n"),
            "station JO62QM: lat 52.5208 lon 13.3750 (the centre of the square)\r\nok\r\n");
  EXPECT_EQ(values().get(Id::kStationLatDeg), 52.5208);
  EXPECT_EQ(values().get(Id::kStationLonDeg), 13.375);
  EXPECT_EQ(ask("setup station 48.1458, 11.625\n"), "station lat 48.1458 lon 11.6250\r\nok\r\n");
  EXPECT_EQ(values().get(Id::kStationLonDeg), 11.625);
  // Not a place: refused with the reason, nothing changed.
  EXPECT_EQ(last_line(ask("setup station ZZ99\n")).rfind("error: ", 0), 0u);
  EXPECT_EQ(last_line(ask("setup station 95 10\n")).rfind("error: ", 0), 0u);
  EXPECT_EQ(values().get(Id::kStationLatDeg), 48.1458);
}

TEST_F(ConsoleTest, CommissionStartsReportsAndStopAbortsIt) {
  EXPECT_EQ(ask("commission accept\n"),
            "error: nothing changed: no finished self-commissioning to accept\r\n");
  EXPECT_EQ(last_line(ask("commission az speeds\n")),
            "error: the speeds step needs the direction and ends steps first");
  EXPECT_EQ(ask("commission az sideways\n"),
            "error: unknown step (all, direction, ends, speeds or bearing)\r\n");
  EXPECT_EQ(ask("commission az all 10\n"),
            "error: the ends are two numbers in degrees: ccw_deg cw_deg\r\n");
  EXPECT_EQ(last_line(ask("commission az all 0 450\n")).rfind("ok commissioning az started", 0),
            0u);
  r.run_ms(100);
  EXPECT_NE(ask("commission status\n").find("commission az state=running step=noise"),
            std::string::npos);
  EXPECT_EQ(ask("stop\n"), "ok stopped\r\n");
  const std::string status = ask("commission status\n");
  EXPECT_NE(status.find("commission az state=aborted step=noise reason=STOP\r\n"),
            std::string::npos)
      << status;
  EXPECT_EQ(last_line(status), "ok");
}

TEST_F(ConsoleTest, AReadOnlyLineMayFollowCommissioningButNotStartIt) {
  values().set(Id::kAccessLineControl, 0);
  const std::string refused = ask("commission az\n");
  EXPECT_EQ(refused.rfind("error: read-only", 0), 0u) << refused;
  EXPECT_EQ(ask("commission accept\n"), refused);
  EXPECT_EQ(ask("setup model hygain-ham4\n"), refused);
  EXPECT_EQ(last_line(ask("commission status\n")), "ok");
  EXPECT_FALSE(r.controller->commissioning().running());
}

}  // namespace
}  // namespace rotord::protocol
