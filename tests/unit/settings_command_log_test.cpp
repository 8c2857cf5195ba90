// Settings writes, calibration and commissioning in the command layer
// (command/settings_commands.hpp, calibration.hpp, commission_commands.hpp;
// issue 25): REST and the console call the same commands, so the same
// change, refused or done, writes the same log line from either; and a
// secret's value never reaches the log, only its key.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "command/command_log.hpp"
#include "fake_crypto.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "iss_elements.hpp"
#include "memory_storage.hpp"
#include "protocol/console_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "string_sink.hpp"
#include "web/http_session.hpp"

namespace rotord::command {
namespace {

using rotord::testing::ask;
using rotord::testing::HttpResponse;
using rotord::testing::LineSink;
using rotord::testing::StringSink;

const access::Peer kWebClient = access::Peer::from_ipv4(0x0A000002);  // 10.0.0.2
const access::Peer kNetClient = access::Peer::from_ipv4(0x0A000003);  // 10.0.0.3

/// One controller with its command log, its REST API and a console.
struct Rig {
  Rig() {
    defaults = r.settings;
    r.run_ms(50);
    r.controller->attach_journal(&log);
    api.poll(now);
  }
  web::ApiContext context() {
    web::ApiContext c{*r.controller, &storage, &defaults, nullptr, "9.9.9"};
    c.crypto = &crypto;
    c.pbkdf2_iterations = 3000;
    c.pbkdf2_slice = 1000;
    c.tles = tles.get();
    c.tle_storage = &tle_storage;
    return c;
  }
  rotord::testing::FakeRotator r;
  settings::Settings defaults;
  rotord::testing::MemoryStorage storage;
  rotord::testing::FakeCrypto crypto;
  // On the heap: two rigs on the stack of the M0 unit tests (qemu) are enough.
  std::unique_ptr<tracking::TleCatalog> tles = std::make_unique<tracking::TleCatalog>();
  rotord::testing::MemoryStorage tle_storage;
  LineSink out;
  CommandLog log{out};
  Millis now = 1000;
  web::Api api{context()};
  settings::Settings scratch;
  protocol::ConsolePort port{&defaults, &scratch, nullptr, "test board"};

  HttpResponse post(const std::string& path, const std::string& body,
                    const std::string& extra = "") {
    return send("POST", path, body, extra);
  }
  /// A request of any method (PUT and DELETE /api/tle) with a JSON body.
  HttpResponse send(const std::string& method, const std::string& path, const std::string& body,
                    const std::string& extra = "") {
    web::HttpSession session(api);
    session.set_peer(kWebClient);
    StringSink sink;
    std::string type = "application/json";
    if (!extra.empty()) type += "\r\n" + extra.substr(0, extra.size() - 2);  // a header more
    session.receive(rotord::testing::post_request(path, body, type).replace(0, 4, method), sink);
    for (int n = 0; n < 20 && sink.data.empty(); ++n) {
      now += 10;
      api.poll(now);
      session.poll(now, sink);
    }
    const auto rs = rotord::testing::parse_responses(sink.data);
    return rs.empty() ? HttpResponse{} : rs[0];
  }
  std::string console(const std::string& line, access::Peer peer = access::Peer::line()) {
    protocol::ConsoleSession session{*r.controller, "9.9.9", &port};
    session.set_peer(peer);
    return ask(session, line + "\n");
  }
  /// A token (`scope`: control or read), with access control turned on by a
  /// web password (the first time).
  std::string control_token(const std::string& scope = "control") {
    if (cookie.empty()) {
      const HttpResponse on = post("/api/password", R"({"password":"correct horse"})");
      EXPECT_EQ(on.status, 200) << on.body;
      const std::string set = on.header("Set-Cookie");
      cookie = "Cookie: " + set.substr(0, set.find(';')) + "\r\n";
    }
    const HttpResponse t =
        post("/api/tokens", R"({"name":")" + scope + R"(","scope":")" + scope + "\"}", cookie);
    EXPECT_EQ(t.status, 201) << t.body;
    return "Authorization: Bearer " + t.body.substr(t.body.find("rtd_"), 36) + "\r\n";
  }
  std::string cookie;  ///< the web login's, once a password is set
  std::string last() const { return out.lines.empty() ? "" : out.lines.back(); }
};

/// A line without its front end and client: what must be equal.
std::string without_sender(const std::string& line) {
  // Not std::regex: GCC 12 warns inside <regex> under the ASan preset's -Werror.
  const std::size_t from = line.find(" from ");
  const std::size_t end = from == std::string::npos ? from : line.find(": ", from);
  if (end == std::string::npos) return line;
  return line.substr(0, from) + " from *" + line.substr(end);
}

TEST(SettingsCommandLog, RestAndConsoleWriteTheSameLineForASettingChange) {
  Rig rest, console;
  ASSERT_EQ(rest.post("/api/settings", R"({"az.offset_deg": 5})").status, 200);
  EXPECT_EQ(console.console("set az.offset_deg 5"), "ok az.offset_deg=5\r\n");
  EXPECT_EQ(rest.last(), "command set az.offset_deg from rest (10.0.0.2): OK");
  EXPECT_EQ(console.last(), "command set az.offset_deg from console (a serial port): OK");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  // A value the table refuses: the same word from either.
  EXPECT_EQ(rest.post("/api/settings", R"({"az.offset_deg": 9999})").status, 422);
  EXPECT_EQ(console.console("set az.offset_deg 9999").rfind("error: az.offset_deg: ", 0), 0u);
  EXPECT_EQ(rest.last(), "command set az.offset_deg from rest (10.0.0.2): INVALID ARGUMENT");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  // The console's import is the same command as POST /api/settings.
  EXPECT_EQ(console.console(R"(import {"park.az_deg": 10, "az.offset_deg": 4})"),
            "ok 2 settings changed\r\n");
  ASSERT_EQ(rest.post("/api/settings", R"({"park.az_deg": 10, "az.offset_deg": 4})").status, 200);
  EXPECT_EQ(rest.last(), "command set park.az_deg az.offset_deg from rest (10.0.0.2): OK");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
}

TEST(SettingsCommandLog, ARefusedKeyIsLoggedDeniedByEitherFrontEnd) {
  Rig rest, console;
  const std::string token = rest.control_token();
  const HttpResponse refused =
      rest.post("/api/settings", R"({"access.control_networks": "10.0.0.0/8"})", token);
  EXPECT_EQ(refused.status, 403);
  EXPECT_NE(refused.body.find("access.control_networks needs the web login, not a token"),
            std::string::npos)
      << refused.body;
  EXPECT_EQ(rest.last(), "command set access.control_networks from rest (10.0.0.2): DENIED");
  EXPECT_EQ(console.console("set access.control_networks 10.0.0.0/8", kNetClient),
            "error: access.control_networks is set through the web only\r\n");
  EXPECT_EQ(console.last(), "command set access.control_networks from console (10.0.0.3): DENIED");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  // A secret: a token and a network client are refused it alike.
  EXPECT_EQ(rest.post("/api/settings", R"({"wifi.password": "n3tw0rkSecret"})", token).status, 403);
  EXPECT_EQ(console.console("set wifi.password n3tw0rkSecret", kNetClient),
            "error: wifi.password is a password: set it over USB or serial, not the network\r\n");
  EXPECT_EQ(console.last(), "command set wifi.password from console (10.0.0.3): DENIED");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  EXPECT_EQ(console.r.settings.text(settings::Id::kWifiPassword), "");
}

// rotctld's `C` (and Easycomm's `CW`) are the same settings write, under
// the line protocols' rule: never a secret or an access rule, whoever asks.
TEST(SettingsCommandLog, RotctldsSetConfIsTheSameCommand) {
  Rig rest, rotctld;
  ASSERT_EQ(rest.post("/api/settings", R"({"park.az_deg": 90})").status, 200);
  protocol::RotctldSession session{*rotctld.r.controller, "1"};
  session.set_peer(kNetClient);
  EXPECT_EQ(ask(session, "C park.az_deg 90\nC wifi.password r0tctldSecret\n"), "RPRT 0\nRPRT -9\n");
  ASSERT_EQ(rotctld.out.lines.size(), 2u);
  EXPECT_EQ(rotctld.out.lines[0], "command set park.az_deg from rotctld (10.0.0.3): OK");
  EXPECT_EQ(without_sender(rest.last()), without_sender(rotctld.out.lines[0]));
  EXPECT_EQ(rotctld.out.lines[1], "command set wifi.password from rotctld (10.0.0.3): DENIED");
}

TEST(SettingsCommandLog, ASecretsValueNeverReachesTheLog) {
  Rig rig;
  EXPECT_EQ(rig.console("set wifi.password Sup3rSecretValue"),
            "ok wifi.password=******** (takes effect after a reboot)\r\n");
  EXPECT_EQ(rig.console(R"(import {"wifi.ap_password": "Imp0rtedSecret"})").rfind("ok ", 0), 0u);
  EXPECT_EQ(rig.post("/api/settings", R"({"mqtt.password": "Br0kerSecret"})").status, 200);
  EXPECT_EQ(rig.console("set wifi.password N3tworkSecret", kNetClient).rfind("error: ", 0), 0u);
  EXPECT_EQ(rig.r.settings.text(settings::Id::kWifiPassword), "Sup3rSecretValue");
  ASSERT_EQ(rig.out.lines.size(), 4u);
  EXPECT_EQ(rig.out.lines[0], "command set wifi.password from console (a serial port): OK");
  EXPECT_EQ(rig.out.lines[1], "command set wifi.ap_password from console (a serial port): OK");
  EXPECT_EQ(rig.out.lines[2], "command set mqtt.password from rest (10.0.0.2): OK");
  EXPECT_EQ(rig.out.lines[3], "command set wifi.password from console (10.0.0.3): DENIED");
  for (const std::string& line : rig.out.lines)
    for (const char* secret :
         {"Sup3rSecretValue", "Imp0rtedSecret", "Br0kerSecret", "N3tworkSecret", "Secret"})
      EXPECT_EQ(line.find(secret), std::string::npos) << line;
}

TEST(SettingsCommandLog, CalibrationFromTheConsoleAndGs232WritesOneLine) {
  Rig console, gs232;
  for (Rig* rig : {&console, &gs232}) {
    rig->r.az.adc.counts = 300;
    rig->r.run_ms(500);
  }
  EXPECT_EQ(console.console("cal az hi"),
            "ok az hi point set from the sensor's present reading\r\n");
  protocol::Gs232Session session{*gs232.r.controller};
  session.set_peer(kNetClient);
  ask(session, "F\r");
  EXPECT_EQ(console.last(), "command cal az hi from console (a serial port): OK");
  EXPECT_EQ(gs232.last(), "command cal az hi from gs232 (10.0.0.3): OK");
  EXPECT_EQ(console.console("cal el lo"),
            "ok el lo point set from the sensor's present reading\r\n");
  EXPECT_EQ(console.last(), "command cal el lo from console (a serial port): OK");
}

TEST(SettingsCommandLog, CommissioningAndSetUpWriteTheSameLineFromRestAndConsole) {
  Rig rest, console;
  // A step that needs others first: refused, with the same word from either.
  EXPECT_EQ(rest.post("/api/commission", R"({"axis": "az", "step": "speeds"})").status, 422);
  EXPECT_EQ(console.console("commission az speeds").rfind("error: ", 0), 0u);
  EXPECT_EQ(rest.last(), "command commission az speeds from rest (10.0.0.2): INVALID ARGUMENT");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  ASSERT_EQ(rest.post("/api/commission", R"({"axis": "az", "step": "direction"})").status, 200);
  EXPECT_EQ(console.console("commission az direction").rfind("ok commissioning az started", 0), 0u);
  EXPECT_EQ(rest.last(), "command commission az direction from rest (10.0.0.2): OK");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  // Nothing to accept yet.
  EXPECT_EQ(rest.post("/api/commission/accept", "{}").status, 409);
  EXPECT_EQ(console.console("commission accept").rfind("error: nothing changed", 0), 0u);
  EXPECT_EQ(rest.last(), "command commission accept from rest (10.0.0.2): INVALID ARGUMENT");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  // A rotator model's figures.
  ASSERT_EQ(rest.post("/api/setup/model", R"({"model": "yaesu-g5500"})").status, 200);
  EXPECT_EQ(console.console("setup model yaesu-g5500").find("error"), std::string::npos);
  EXPECT_EQ(rest.last(), "command setup model from rest (10.0.0.2): OK");
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  EXPECT_EQ(console.console("setup station JO62"),
            "station JO62: lat 52.5000 lon 13.0000 (the centre of the square)\r\nok\r\n");
  EXPECT_EQ(console.last(), "command setup station from console (a serial port): OK");
}

// A REST preset is a settings row (preset.N) written by the command layer's
// settings write: the console's `set preset.N` line, saved before the
// answer, and undone when saving fails.
TEST(SettingsCommandLog, ARestPresetIsTheSettingsWriteOfItsRow) {
  Rig rest, console;
  const HttpResponse saved = rest.post("/api/presets", R"({"name": "EU", "az": 45})");
  ASSERT_EQ(saved.status, 200) << saved.body;
  EXPECT_EQ(saved.body,
            R"({"max":16,"presets":[{"slot":1,"name":"EU","az_deg":45,"long_path":false}]})");
  EXPECT_EQ(rest.last(), "command set preset.1 from rest (10.0.0.2): OK");
  EXPECT_EQ(console.console("set preset.1 45:EU").rfind("ok preset.1=", 0), 0u);
  EXPECT_EQ(without_sender(rest.last()), without_sender(console.last()));
  EXPECT_NE(rest.storage.document.find(R"("preset.1": "45.0:EU")"), std::string::npos)
      << rest.storage.document;
  // Saving fails: the same answer as before, the row undone, STORAGE.
  rest.storage.fail = true;
  const HttpResponse lost = rest.post("/api/presets", R"({"name": "JA", "az": 330})");
  EXPECT_EQ(lost.status, 500);
  EXPECT_EQ(lost.body, R"({"error":"the presets could not be saved; nothing was changed"})");
  EXPECT_EQ(rest.r.settings.text(settings::Id::kPreset2), "");
  EXPECT_EQ(rest.last(), "command set preset.2 from rest (10.0.0.2): STORAGE");
  // A delete empties the row (the console's preset, deleted over REST).
  const HttpResponse gone = console.post("/api/presets/delete", R"({"name": "EU"})");
  EXPECT_EQ(gone.status, 200);
  EXPECT_EQ(gone.body, R"({"max":16,"presets":[]})");
  EXPECT_EQ(console.last(), "command set preset.1 from rest (10.0.0.2): OK");
  // No such preset: nothing written, no line, as a body that cannot be read.
  const std::size_t lines = console.out.lines.size();
  EXPECT_EQ(console.post("/api/presets/delete", R"({"name": "EU"})").status, 404);
  EXPECT_EQ(console.out.lines.size(), lines);
}

// Storing and removing TLEs are commands with their line: how many objects
// a paste stored, or why none; the object removed.
TEST(SettingsCommandLog, StoringAndRemovingTlesWriteTheirLine) {
  Rig rig;
  HttpResponse r = rig.send("PUT", "/api/tle", rotord::testing::iss_tle_text());
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, R"({"ok":true,"added":1,"replaced":0,"count":1,"saved":true})");
  EXPECT_EQ(rig.last(), "command tle 1 object from rest (10.0.0.2): OK");
  r = rig.send("PUT", "/api/tle", "ISS (ZARYA)\n1 25544U\n");
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(rig.last(), "command tle from rest (10.0.0.2): INVALID ARGUMENT");
  rig.tle_storage.fail = true;
  r = rig.send("PUT", "/api/tle",
               rotord::testing::iss_tle_text() + rotord::testing::twin_tle_text());
  EXPECT_EQ(r.status, 500);
  EXPECT_EQ(r.body, R"({"error":"the TLEs are stored in RAM but could not be saved"})");
  EXPECT_EQ(rig.last(), "command tle 2 objects from rest (10.0.0.2): STORAGE");
  rig.tle_storage.fail = false;
  r = rig.send("DELETE", "/api/tle?object=TWIN", "");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, R"({"ok":true,"count":1})");
  EXPECT_EQ(rig.last(), "command tle delete TWIN from rest (10.0.0.2): OK");
  EXPECT_EQ(rig.send("DELETE", "/api/tle?object=TWIN", "").status, 404);
  EXPECT_EQ(rig.last(), "command tle delete TWIN from rest (10.0.0.2): NOT FOUND");
}

// A settings, preset, set-up or TLE route refused at its gate (a read-only
// token: 403; another operator's control lock, to the web login: 423) is
// logged in the words of its success line, before anything is read; the
// replies are the gate's.
TEST(SettingsCommandLog, ARouteRefusedAtItsGateIsLoggedInItsCommandsWords) {
  struct Refused {
    const char* method;
    const char* path;
    const char* body;
    const char* words;
  };
  const Refused routes[] = {
      {"POST", "/api/settings", R"({"park.az_deg": 10})", "set"},
      {"POST", "/api/presets", R"({"name": "EU", "az": 45})", "set"},
      {"POST", "/api/presets/delete", R"({"name": "EU"})", "set"},
      {"POST", "/api/settings/reset", "{}", "reset settings"},
      {"POST", "/api/setup/model", R"({"model": "yaesu-g5500"})", "setup model"},
      {"POST", "/api/commission", R"({"axis": "az", "step": "direction"})", "commission"},
      {"POST", "/api/commission/accept", "{}", "commission accept"},
      {"PUT", "/api/tle", "", "tle"},
      {"DELETE", "/api/tle?object=ISS", "", "tle delete"},
      {"POST", "/api/reboot", "{}", "reboot"},
  };
  Rig rig;
  const std::string reader = rig.control_token("read");
  for (const Refused& route : routes) {
    const HttpResponse denied = rig.send(route.method, route.path, route.body, reader);
    EXPECT_EQ(denied.status, 403) << route.path;
    EXPECT_EQ(rig.last(), std::string("command ") + route.words + " from rest (10.0.0.2): DENIED");
  }
  rig.r.controller->control_lock().take({}, 3600000);
  for (const Refused& route : routes) {
    const HttpResponse locked = rig.send(route.method, route.path, route.body, rig.cookie);
    EXPECT_EQ(locked.status, 423) << route.path << " " << locked.body;
    EXPECT_EQ(rig.last(), std::string("command ") + route.words + " from rest (10.0.0.2): LOCKED");
  }
  EXPECT_EQ(rig.r.settings.get(settings::Id::kParkAzDeg),
            rig.defaults.get(settings::Id::kParkAzDeg));
  EXPECT_EQ(rig.tles->size(), 0u);
}

}  // namespace
}  // namespace rotord::command
