// Text settings (Type::kText): validation by format, secrets that are never
// read back, the mask that keeps a secret, the JSON document and the flash
// slots with the longest values, and what the text protocols print.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "hal/flash.hpp"
#include "http_test_client.hpp"
#include "json/settings_json.hpp"
#include "memory_storage.hpp"
#include "settings/preset.hpp"
#include "settings/settings.hpp"
#include "settings_bases.hpp"
#include "storage/flash_slots.hpp"
#include "util/utc_time.hpp"
#include "web/web_api.hpp"

namespace rotord {
namespace {

using settings::Id;
using settings::kSecretMask;
using settings::Settings;

std::string encode(const Settings& s, web::Secrets secrets = web::Secrets::kMask) {
  rotord::testing::StringSink sink;
  {
    web::JsonWriter w(sink);
    web::write_settings(s, w, secrets);
  }
  return sink.data;
}

web::ApplyOutcome apply(const std::string& json, Settings& target) {
  static Settings scratch;
  static web::SettingErrors errors;
  return web::apply_settings_json(json, target, scratch, errors);
}

TEST(TextSettings, DefaultsComeFromTheTable) {
  const Settings s;
  EXPECT_EQ(s.text(Id::kNetHostname), "rotord");
  EXPECT_EQ(s.text(Id::kTimeSntpServer), "pool.ntp.org");
  EXPECT_EQ(s.text(Id::kNetIpv4Netmask), "255.255.255.0");
  EXPECT_EQ(s.text(Id::kWifiSsid), "");
  EXPECT_EQ(s.text(Id::kAzMaxDeg), "") << "a number has no text";
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(TextSettings, LengthLimitsAndNothingChangesOnError) {
  Settings s;
  const auto revision = s.revision();
  EXPECT_EQ(s.set_text(Id::kWifiSsid, std::string(33, 'x')).error, Error::kOutOfRange);
  EXPECT_EQ(s.set_text(Id::kWifiPassword, "short").error, Error::kOutOfRange);
  EXPECT_EQ(s.set_text(Id::kWifiPassword, std::string(64, 'p')).error, Error::kOutOfRange);
  EXPECT_EQ(s.revision(), revision);
  EXPECT_EQ(s.text(Id::kWifiSsid), "");
  ASSERT_EQ(s.set_text(Id::kWifiSsid, std::string(32, 'x')).error, Error::kOk);
  ASSERT_EQ(s.set_text(Id::kWifiPassword, std::string(63, 'p')).error, Error::kOk);
  EXPECT_EQ(s.text(Id::kWifiSsid), std::string(32, 'x'));
  EXPECT_GT(s.revision(), revision);
  // Empty is "not set" for every text row (an open network, no mDNS).
  EXPECT_EQ(s.set_text(Id::kWifiPassword, "").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetHostname, "").error, Error::kOk);
  EXPECT_EQ(s.set(Id::kWifiSsid, 3).error, Error::kInvalidArgument) << "a number into text";
  EXPECT_EQ(s.set_text(Id::kAzMaxDeg, "400").error, Error::kInvalidArgument);
}

TEST(TextSettings, FormatsRefuseWhatTheNetworkStackCannotUse) {
  Settings s;
  // SSID: UTF-8 allowed (phones show it), control characters and broken UTF-8 not.
  EXPECT_EQ(s.set_text(Id::kWifiSsid, "Caf\xc3\xa9 Wi-Fi").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kWifiSsid, std::string("a\nb")).error, Error::kInvalidArgument);
  EXPECT_EQ(s.set_text(Id::kWifiSsid, "bad \xc3").error, Error::kInvalidArgument);
  EXPECT_EQ(s.set_text(Id::kWifiSsid, "bad \xff\xfe").error, Error::kInvalidArgument);
  // Passphrases: printable ASCII only (WPA2), spaces and quotes included.
  EXPECT_EQ(s.set_text(Id::kWifiPassword, R"(a "quoted" \pass)").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kWifiPassword, "p\xc3\xa4sswort1").error, Error::kInvalidArgument);
  // Host name: one DNS label.
  EXPECT_EQ(s.set_text(Id::kNetHostname, "shack-rotor2").error, Error::kOk);
  for (const char* bad : {"-rotor", "rotor-", "rotor.local", "rot or", "rotor_1"})
    EXPECT_EQ(s.set_text(Id::kNetHostname, bad).error, Error::kInvalidArgument) << bad;
  // SNTP server: a dotted name or an address.
  EXPECT_EQ(s.set_text(Id::kTimeSntpServer, "0.de.pool.ntp.org").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kTimeSntpServer, "192.168.1.1").error, Error::kOk);
  for (const char* bad : {"pool..ntp.org", ".pool", "pool.", "ntp server"})
    EXPECT_EQ(s.set_text(Id::kTimeSntpServer, bad).error, Error::kInvalidArgument) << bad;
}

TEST(TextSettings, DottedQuadsAreStrict) {
  std::uint32_t a = 0;
  ASSERT_TRUE(settings::parse_ipv4("192.168.1.20", a));
  EXPECT_EQ(a, 0xC0A80114u);
  ASSERT_TRUE(settings::parse_ipv4("0.0.0.0", a));
  ASSERT_TRUE(settings::parse_ipv4("255.255.255.255", a));
  EXPECT_EQ(a, 0xFFFFFFFFu);
  for (const char* bad :
       {"", "1.2.3", "1.2.3.4.5", "256.1.1.1", "1.2.3.04", "01.2.3.4", "1..2.3", "1.2.3.4 ",
        " 1.2.3.4", "1.2.3.-4", "a.b.c.d", "1.2.3.4/24", "1234.1.1.1"})
    EXPECT_FALSE(settings::parse_ipv4(bad, a)) << bad;
  Settings s;
  const settings::Rejection r = s.set_text(Id::kNetIpv4Address, "192.168.1.300");
  EXPECT_EQ(r.error, Error::kInvalidArgument);
  EXPECT_NE(std::strstr(r.reason, "IPv4"), nullptr) << r.reason;
}

TEST(TextSettings, StaticAddressingRules) {
  Settings s;
  ASSERT_EQ(s.set_from_text(Id::kNetIpv4Mode, "static").error, Error::kOk);
  EXPECT_NE(std::strstr(s.check_consistency().reason, "net.ipv4_address"), nullptr);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Address, "192.168.1.20").error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk) << s.check_consistency().reason;
  ASSERT_EQ(s.set_text(Id::kNetIpv4Netmask, "255.0.255.0").error, Error::kOk);
  EXPECT_NE(std::strstr(s.check_consistency().reason, "net.ipv4_netmask"), nullptr);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Netmask, "255.255.255.0").error, Error::kOk);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Address, "192.168.1.255").error, Error::kOk);
  EXPECT_NE(std::strstr(s.check_consistency().reason, "broadcast"), nullptr);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Address, "192.168.1.20").error, Error::kOk);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Gateway, "192.168.2.1").error, Error::kOk);
  EXPECT_NE(std::strstr(s.check_consistency().reason, "net.ipv4_gateway"), nullptr);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Gateway, "192.168.1.1").error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
  // dhcp: the static fields are not checked together.
  ASSERT_EQ(s.set_text(Id::kNetIpv4Gateway, "10.0.0.1").error, Error::kOk);
  ASSERT_EQ(s.set_from_text(Id::kNetIpv4Mode, "dhcp").error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
  ASSERT_EQ(s.set_text(Id::kTimeSntpServer, "").error, Error::kOk);
  EXPECT_NE(std::strstr(s.check_consistency().reason, "time.sntp_server"), nullptr);
}

TEST(TextSettings, SecretsAreMaskedAndTheMaskKeepsThem) {
  Settings s;
  EXPECT_EQ(s.visible_text(Id::kWifiPassword), "") << "nothing stored: nothing to hide";
  ASSERT_EQ(s.set_text(Id::kWifiPassword, "correct horse").error, Error::kOk);
  EXPECT_EQ(s.visible_text(Id::kWifiPassword), kSecretMask);
  const auto revision = s.revision();
  EXPECT_EQ(s.set_text(Id::kWifiPassword, kSecretMask).error, Error::kOk);
  EXPECT_EQ(s.text(Id::kWifiPassword), "correct horse");
  EXPECT_EQ(s.revision(), revision);
  // Not a secret: the mask is just text (and for a host name, invalid).
  EXPECT_EQ(s.set_text(Id::kWifiSsid, kSecretMask).error, Error::kOk);
  EXPECT_EQ(s.text(Id::kWifiSsid), kSecretMask);
  char out[80];
  ASSERT_EQ(s.format_value(Id::kWifiPassword, out, sizeof out), std::strlen(kSecretMask));
  EXPECT_STREQ(out, kSecretMask);
  s.format_value(Id::kTimeSntpServer, out, sizeof out);
  EXPECT_STREQ(out, "pool.ntp.org");
}

TEST(TextSettings, ApiDocumentMasksTheStoredDocumentKeeps) {
  Settings s;
  ASSERT_EQ(s.set_text(Id::kWifiPassword, "hunter2-secret").error, Error::kOk);
  ASSERT_EQ(s.set_text(Id::kWifiApPassword, "ap-secret-99").error, Error::kOk);
  const std::string shown = encode(s);
  EXPECT_EQ(shown.find("hunter2"), std::string::npos) << shown;
  EXPECT_EQ(shown.find("ap-secret"), std::string::npos) << shown;
  EXPECT_NE(shown.find(R"("wifi.password":"********")"), std::string::npos) << shown;
  const std::string stored = encode(s, web::Secrets::kReveal);
  EXPECT_NE(stored.find(R"("wifi.password":"hunter2-secret")"), std::string::npos);

  // The API's document written back (an export imported, an untouched form)
  // keeps the secrets; the stored document restores them.
  Settings other;
  ASSERT_EQ(other.set_text(Id::kWifiPassword, "other-device-pw").error, Error::kOk);
  ASSERT_EQ(apply(shown, other).status, web::ApplyOutcome::kApplied);
  EXPECT_EQ(other.text(Id::kWifiPassword), "other-device-pw");
  Settings restored;
  const web::ApplyOutcome r = apply(stored, restored);
  ASSERT_EQ(r.status, web::ApplyOutcome::kApplied) << r.message;
  EXPECT_EQ(restored.text(Id::kWifiPassword), "hunter2-secret");
  EXPECT_EQ(restored.text(Id::kWifiApPassword), "ap-secret-99");
  EXPECT_TRUE(r.changed.test(static_cast<std::size_t>(Id::kWifiPassword)));
}

TEST(TextSettings, JsonRefusesWrongTypesAndOverlongText) {
  Settings s;
  static web::SettingErrors errors;
  static Settings scratch;
  const std::string too_long = R"({"time.sntp_server":")" + std::string(200, 'a') + R"("})";
  for (const std::string& doc :
       {std::string(R"({"wifi.ssid":42})"), std::string(R"({"wifi.ssid":null})"),
        std::string(R"({"wifi.ssid":["a"]})"), std::string(R"({"net.ipv4_address":"1.2.3"})"),
        std::string(R"({"wifi.password":"\u0001\u0002abcdefgh"})"), too_long}) {
    const web::ApplyOutcome r = web::apply_settings_json(doc, s, scratch, errors);
    EXPECT_EQ(r.status, web::ApplyOutcome::kInvalid) << doc;
    ASSERT_GT(errors.size(), 0u) << doc;
    EXPECT_GT(std::strlen(errors[0].reason), 0u);
  }
  EXPECT_EQ(s.text(Id::kTimeSntpServer), "pool.ntp.org");
  // Escapes decode: a quote and a backslash in a passphrase, a \u00e9 in an SSID.
  ASSERT_EQ(apply(R"({"wifi.password":"a\"b\\c d e f","wifi.ssid":"Caf\u00e9"})", s).status,
            web::ApplyOutcome::kApplied);
  EXPECT_EQ(s.text(Id::kWifiPassword), "a\"b\\c d e f");
  EXPECT_EQ(s.text(Id::kWifiSsid), "Caf\xc3\xa9");
}

/// hal::Flash in RAM with the Pico W's geometry (4 KB sectors, 256 B pages).
class RamFlash final : public hal::Flash {
 public:
  explicit RamFlash(std::size_t bytes) : mem_(bytes, 0xFF) {}
  std::size_t size() const override { return mem_.size(); }
  std::size_t erase_size() const override { return 4096; }
  std::size_t program_size() const override { return 256; }
  bool read(std::size_t offset, void* out, std::size_t n) override {
    std::memcpy(out, mem_.data() + offset, n);
    return true;
  }
  bool erase(std::size_t offset, std::size_t n) override {
    std::memset(mem_.data() + offset, 0xFF, n);
    return true;
  }
  bool program(std::size_t offset, const void* data, std::size_t n) override {
    std::memcpy(mem_.data() + offset, data, n);
    return true;
  }

 private:
  std::vector<unsigned char> mem_;
};

/// Every text at its maximum length, with the characters that need escaping.
Settings longest_texts() {
  Settings s;
  const std::string quotes(63, '"');  // each written as \" : twice the bytes
  EXPECT_EQ(s.set_text(Id::kWifiPassword, quotes).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kWifiApPassword, std::string(63, '\\')).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kWifiSsid, std::string(32, '"')).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetHostname, std::string(32, 'h')).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kTimeSntpServer, std::string(63, 'n')).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Address, "192.168.100.200").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Netmask, "255.255.255.128").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Gateway, "192.168.100.129").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Dns, "192.168.100.254").error, Error::kOk);
  // Sixteen presets at their longest (a name is 20 bytes, no escapes).
  for (std::size_t n = 0; n < settings::kPresetCount; ++n)
    EXPECT_EQ(s.set_text(settings::preset_id(n), "359.9L:" + std::string(20, 'p')).error,
              Error::kOk);
  return s;
}

TEST(TextSettings, LongestDocumentFitsTheApiBufferAndAFlashSlot) {
  const Settings s = longest_texts();
  char buf[web::Api::kMaxDocumentBytes];
  rotord::testing::MemoryStorage memory;
  // The user's layer at its largest: every row differs from the base.
  const Settings base = rotord::testing::differs_everywhere(s);
  ASSERT_TRUE(web::save_settings(memory, s, base, buf, sizeof buf))
      << "the stored document outgrew Api::kMaxDocumentBytes";
  const std::size_t n = memory.document.size();
  // Room for about 30 more rows before Api::kMaxDocumentBytes must grow.
  EXPECT_LT(n + 1024, sizeof buf) << n << " bytes";

  RamFlash flash(32 * 1024);  // two 16 KB slots, as ports/pico_w
  FlashSlots slots(flash);
  ASSERT_TRUE(slots.usable());
  EXPECT_GE(slots.capacity(), sizeof buf);
  ASSERT_TRUE(web::save_settings(slots, s, base, buf, sizeof buf));
  Settings loaded;
  Settings scratch;
  char load_buf[web::Api::kMaxDocumentBytes];
  const web::LoadOutcome r =
      web::load_settings(slots, base, nullptr, loaded, scratch, load_buf, sizeof load_buf);
  ASSERT_EQ(r.status, web::LoadOutcome::kLoaded) << r.reason << " " << r.key;
  for (std::size_t k = 0; k < settings::kCount; ++k)
    EXPECT_TRUE(loaded.same_value(static_cast<Id>(k), s)) << settings::def(static_cast<Id>(k)).key;
}

TEST(TextSettings, GarbageInTheStoredDocumentKeepsTheDefaults) {
  Settings s;
  for (const char* doc :
       {R"({"wifi.ssid":"unterminated)", R"({"wifi.ssid":"a","wifi.ssid":"b"})",
        R"({"net.hostname":"bad host"})", "\xff\xfe{}", R"({"wifi.password":"\ud800xxxxxxxx"})"}) {
    EXPECT_NE(apply(doc, s).status, web::ApplyOutcome::kApplied) << doc;
    EXPECT_EQ(s.text(Id::kWifiSsid), "");
    EXPECT_EQ(s.text(Id::kNetHostname), "rotord");
  }
}

TEST(TextSettings, ProtocolWritesUndoARuleBreak) {
  Settings s;
  ASSERT_EQ(s.update_from_text(Id::kNetIpv4Address, "10.1.2.3").error, Error::kOk);
  ASSERT_EQ(s.update_from_text(Id::kNetIpv4Mode, "static").error, Error::kOk);
  EXPECT_NE(s.update_from_text(Id::kNetIpv4Address, "").error, Error::kOk);
  EXPECT_EQ(s.text(Id::kNetIpv4Address), "10.1.2.3") << "undone";
  // Numbers go through the same path (fuzz_rotctld found a memcpy from the
  // null data() of a number's empty text view here).
  ASSERT_EQ(s.update_from_text(Id::kParkAzDeg, "12.5").error, Error::kOk);
  EXPECT_EQ(s.get(Id::kParkAzDeg), 12.5);
  ASSERT_EQ(s.set_text(Id::kWifiSsid, std::string_view()).error, Error::kOk);
  char out[8];
  EXPECT_EQ(s.format_value(Id::kWifiApPassword, out, sizeof out), 0u);
  // Text is taken as is: spaces belong to an SSID.
  ASSERT_EQ(s.update_from_text(Id::kWifiSsid, " My Net ").error, Error::kOk);
  EXPECT_EQ(s.text(Id::kWifiSsid), " My Net ");
}

TEST(UtcTime, FormatsIso8601) {
  char out[32];
  ASSERT_GT(format_utc_iso8601(0, out, sizeof out), 0u);
  EXPECT_STREQ(out, "1970-01-01T00:00:00.000Z");
  ASSERT_GT(format_utc_iso8601(951'782'400'000 + 1, out, sizeof out), 0u);  // leap day 2000
  EXPECT_STREQ(out, "2000-02-29T00:00:00.001Z");
  ASSERT_GT(format_utc_iso8601(4'107'542'399'999, out, sizeof out), 0u);
  EXPECT_STREQ(out, "2100-02-28T23:59:59.999Z");
  ASSERT_GT(format_utc_iso8601(-1, out, sizeof out), 0u);
  EXPECT_STREQ(out, "1969-12-31T23:59:59.999Z");
  EXPECT_EQ(format_utc_iso8601(0, out, 10), 0u) << "too small a buffer";
}

TEST(UtcTime, TimeBaseFollowsTheMonotonicClock) {
  TimeBase base;
  EXPECT_FALSE(base.unix_ms(5000).has_value());
  // SNTP: 2026-11-23T17:40:11.250 at monotonic 5 s.
  base.set(unix_ms_from_sntp(1'795'455'611u, 250'999u), 5000);
  EXPECT_EQ(*base.unix_ms(5000), 1'795'455'611'250);
  EXPECT_EQ(*base.unix_ms(65'000), 1'795'455'671'250);
}

}  // namespace
}  // namespace rotord
