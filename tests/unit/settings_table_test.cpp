#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <optional>
#include <string>

#include "settings/applies.hpp"
#include "settings/settings.hpp"

namespace rotord::settings {
namespace {

TEST(SettingsTable, EveryRowIsWellFormed) {
  for (std::size_t n = 0; n < kCount; ++n) {
    const Def& d = def(static_cast<Id>(n));
    SCOPED_TRACE(d.key);
    EXPECT_GT(std::strlen(d.key), 0u);
    if (d.type == Type::kText) {
      // min/max are lengths; the default text is in the choices column.
      EXPECT_LE(d.min, d.max);
      EXPECT_EQ(validate_text(static_cast<Id>(n), d.choices).error, Error::kOk);
    } else {
      EXPECT_LE(d.min, d.default_value);
      EXPECT_GE(d.max, d.default_value);
    }
    EXPECT_EQ(find(d.key), static_cast<Id>(n)) << "duplicate key";
    if (d.type == Type::kEnum) {
      EXPECT_EQ(choice_count(static_cast<Id>(n)), static_cast<int>(d.max) + 1);
    }
  }
}

// Issue 24: every row speaks the owner's words, in one of the owner's
// groups, and its condition (what hides it in the form) can be read. (Its
// help is checked where it is served: web/tools/settings_help.mjs fails the
// build on a row without one, web.browser.settings shows each.)
TEST(SettingsTable, EveryRowHasALabelAGroupAndAReadableCondition) {
  const auto groups = settings::groups();
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    const Def& d = def(id);
    SCOPED_TRACE(d.key);
    const std::string label = d.label;
    EXPECT_GE(label.size(), 3u);
    EXPECT_LE(label.size(), 48u) << "a label is a few words; the help says the rest";
    EXPECT_NE(label, d.key) << "a label in words, not the key";
    EXPECT_EQ(label.find('_'), std::string::npos) << "no key in a label";
    EXPECT_TRUE(std::isupper(static_cast<unsigned char>(label[0]))) << label;
    EXPECT_NE(label.back(), '.') << "a label, not a sentence";
    bool known = false;
    for (const char* g : groups) known = known || std::strcmp(g, d.group) == 0;
    EXPECT_TRUE(known) << d.group;
    const char* error = condition_error(condition(id));
    EXPECT_EQ(error, nullptr) << condition(id) << ": " << (error ? error : "");
  }
}

// The elevation's labels are derived from the azimuth's (axis_label.hpp),
// which lowers the first letter after "Elevation: ": never an acronym's
// ("Elevation: pWM duty ..." and "Elevation: mA3 ..." were shown).
TEST(SettingsTable, DerivedElevationLabelsKeepTheAcronyms) {
  const auto acronym = [](const std::string& word) {
    return word.size() > 1 && std::isupper(static_cast<unsigned char>(word[0])) &&
           (std::isupper(static_cast<unsigned char>(word[1])) ||
            std::isdigit(static_cast<unsigned char>(word[1])));
  };
  int checked = 0;
  for (std::size_t n = 0; n < kCount; ++n) {
    const Def& el = def(static_cast<Id>(n));
    if (std::strncmp(el.key, "el.", 3) != 0) continue;
    const std::optional<Id> az_id = find("az." + std::string(el.key + 3));
    if (!az_id) continue;
    const std::string az_label = def(*az_id).label;
    const std::string el_label = el.label;
    SCOPED_TRACE(el.key);
    std::size_t at = 0;
    while (at < az_label.size()) {
      const std::size_t end = std::min(az_label.find(' ', at), az_label.size());
      const std::string word = az_label.substr(at, end - at);
      if (acronym(word)) {
        EXPECT_NE(el_label.find(word), std::string::npos) << el_label << " lost " << word;
        ++checked;
      }
      at = end + 1;
    }
  }
  EXPECT_GE(checked, 4) << "PWM and MA3 at least";
}

TEST(SettingsTable, LabelsAreUniqueWhereTheyCanBeSeenTogether) {
  // The Pico W's pins and the Raspberry Pi's lines share their labels: never
  // on one platform together. Everything else is told apart by its label.
  for (std::size_t a = 0; a < kCount; ++a) {
    for (std::size_t b = a + 1; b < kCount; ++b) {
      const Def& x = def(static_cast<Id>(a));
      const Def& y = def(static_cast<Id>(b));
      if (std::strcmp(x.label, y.label) != 0) continue;
      bool together = false;
      for (const Platform p : {Platform::kPicoW, Platform::kGpiod, Platform::kSim}) {
        Settings all;
        // Every bool on: the widest set of rows a platform can show.
        for (std::size_t n = 0; n < kCount; ++n)
          if (def(static_cast<Id>(n)).type == Type::kBool) all.set(static_cast<Id>(n), 1);
        together = together ||
                   (applies(static_cast<Id>(a), all, p) && applies(static_cast<Id>(b), all, p));
      }
      EXPECT_FALSE(together) << x.key << " and " << y.key << " are both \"" << x.label << "\"";
    }
  }
}

TEST(SettingsConditions, ThePlatformAndTheDriveDecideWhatApplies) {
  Settings s;  // relay drive, pot sensor, no elevation, no brake
  // The Pico W's pins on the Pico W, the Raspberry Pi's lines on the Pi,
  // neither in the simulator.
  EXPECT_TRUE(applies(Id::kPinAzCw, s, Platform::kPicoW));
  EXPECT_FALSE(applies(Id::kPinAzCw, s, Platform::kGpiod));
  EXPECT_FALSE(applies(Id::kPinAzCw, s, Platform::kSim));
  EXPECT_TRUE(applies(Id::kGpiodAzCw, s, Platform::kGpiod));
  EXPECT_FALSE(applies(Id::kGpiodAzCw, s, Platform::kPicoW));
  EXPECT_TRUE(applies(Id::kWifiSsid, s, Platform::kPicoW));
  EXPECT_FALSE(applies(Id::kWifiSsid, s, Platform::kGpiod));
  // Told nothing: every platform's rows.
  EXPECT_TRUE(applies(Id::kWifiSsid, s, Platform::kUnknown));
  EXPECT_TRUE(applies(Id::kGpiodAzCw, s, Platform::kUnknown));
  // The drive: relays, or the H-bridge's PWM; a slow zone only where there
  // is a slow speed.
  EXPECT_FALSE(applies(Id::kPinAzPwmCw, s, Platform::kPicoW));
  EXPECT_FALSE(applies(Id::kAzSlowZoneDeg, s, Platform::kSim));
  EXPECT_FALSE(applies(Id::kAzPwmSlowDuty, s, Platform::kSim));
  ASSERT_EQ(s.set_from_text(Id::kAzDrive, "hbridge").error, Error::kOk);
  EXPECT_TRUE(applies(Id::kPinAzPwmCw, s, Platform::kPicoW));
  EXPECT_FALSE(applies(Id::kPinAzCw, s, Platform::kPicoW));
  EXPECT_TRUE(applies(Id::kAzSlowZoneDeg, s, Platform::kSim));
  EXPECT_TRUE(applies(Id::kAzPwmSlowDuty, s, Platform::kSim));
  // Alternatives: the Pi's PWM chip serves either axis's H-bridge.
  EXPECT_TRUE(applies(Id::kPwmChip, s, Platform::kGpiod));
  ASSERT_EQ(s.set_from_text(Id::kAzDrive, "relay").error, Error::kOk);
  EXPECT_FALSE(applies(Id::kPwmChip, s, Platform::kGpiod));
  ASSERT_EQ(s.set_from_text(Id::kElEnabled, "true").error, Error::kOk);
  ASSERT_EQ(s.set_from_text(Id::kElDrive, "hbridge").error, Error::kOk);
  EXPECT_TRUE(applies(Id::kPwmChip, s, Platform::kGpiod));
  // A bool, and a number that is not 0.
  EXPECT_FALSE(applies(Id::kAzBrakeReleaseMs, s, Platform::kSim));
  ASSERT_EQ(s.set_from_text(Id::kAzHasBrake, "true").error, Error::kOk);
  EXPECT_TRUE(applies(Id::kAzBrakeReleaseMs, s, Platform::kSim));
  ASSERT_EQ(s.set_from_text(Id::kSlipDeg, "0").error, Error::kOk);
  EXPECT_FALSE(applies(Id::kSlipFault, s, Platform::kSim));
  // A text that is not empty.
  EXPECT_FALSE(applies(Id::kTrackTleRefreshH, s, Platform::kGpiod));
  ASSERT_EQ(s.set_text(Id::kTrackTleUrl, "https://celestrak.org/x").error, Error::kOk);
  EXPECT_TRUE(applies(Id::kTrackTleRefreshH, s, Platform::kGpiod));
}

TEST(SettingsConditions, AConditionThatCannotBeReadIsNamed) {
  EXPECT_EQ(condition_error(""), nullptr);
  EXPECT_EQ(condition_error("platform=pico_w&az.drive=hbridge;el.enabled"), nullptr);
  EXPECT_STREQ(condition_error("az.drv=relay"), "unknown key in a condition");
  EXPECT_STREQ(condition_error("az.drive=warp"), "a choice the setting does not have");
  EXPECT_STREQ(condition_error("platform=arduino"), "unknown platform");
  EXPECT_STREQ(condition_error("platform"), "platform needs =pico_w, =gpiod or =sim");
  EXPECT_EQ(condition_error("wifi.ssid"), nullptr);  // a text that is not empty
  EXPECT_STREQ(condition_error("az.min_deg=3"), "=choice needs an enum setting");
  EXPECT_STREQ(condition_error("el.enabled&"), "an empty term");
}

TEST(SettingsTable, DefaultsAreConsistent) {
  Settings s;
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(Settings, RejectsOutOfRangeAndKeepsTheOldValue) {
  Settings s;
  const double before = s.get(Id::kAzToleranceDeg);
  const auto revision = s.revision();
  EXPECT_EQ(s.set(Id::kAzToleranceDeg, 50).error, Error::kOutOfRange);
  EXPECT_EQ(s.set_from_text(Id::kAzToleranceDeg, "abc").error, Error::kInvalidArgument);
  EXPECT_EQ(s.set(Id::kNetMaxClients, 2.5).error, Error::kInvalidArgument);
  EXPECT_EQ(s.get(Id::kAzToleranceDeg), before);
  EXPECT_EQ(s.revision(), revision);
}

TEST(Settings, ParsesBooleansEnumsAndNumbers) {
  Settings s;
  EXPECT_EQ(s.set_from_text(Id::kAzContinuous, "true").error, Error::kOk);
  EXPECT_TRUE(s.b(Id::kAzContinuous));
  EXPECT_EQ(s.set_from_text(Id::kAzDrive, "hbridge").error, Error::kOk);
  EXPECT_EQ(s.i(Id::kAzDrive), 3);
  EXPECT_EQ(s.set_from_text(Id::kAzDrive, "warp").error, Error::kInvalidArgument);
  EXPECT_EQ(s.set_from_text(Id::kAzOffsetDeg, "-12,5").error, Error::kOk);
  EXPECT_FLOAT_EQ(s.f(Id::kAzOffsetDeg), -12.5f);
  char buf[32];
  Settings::format(Id::kAzDrive, s.get(Id::kAzDrive), buf, sizeof buf);
  EXPECT_STREQ(buf, "hbridge");
}

TEST(Settings, FloatsAreWrittenInTheFewestDigitsThatReadBackTheSame) {
  char buf[kValueTextCapacity];
  Settings::format(Id::kAzPwmSlowDuty, 0.15, buf, sizeof buf);
  EXPECT_STREQ(buf, "0.15");  // as a person typed it
  // Computed values (a pot calibration from a simulated ADC, a third) keep
  // every digit, so an export imported back changes nothing.
  for (const double value : {4095.0 / 66.0, 1.0 / 3.0, -123.45678901, 1e-7}) {
    Settings::format(Id::kAzPotCalLoCounts, value, buf, sizeof buf);
    Settings s;
    ASSERT_EQ(s.set_from_text(Id::kAzOffsetDeg, buf).error, Error::kOk) << buf;
    EXPECT_EQ(s.get(Id::kAzOffsetDeg), value) << buf;
  }
}

TEST(Settings, TheMagnetometerNeedsEitherPortsI2c) {
  Settings s;
  ASSERT_EQ(s.set_from_text(Id::kAzSensor, "mag").error, Error::kOk);
  ASSERT_EQ(s.set(Id::kPinI2cSda, -1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kPinI2cScl, -1).error, Error::kOk);
  const auto pi = s.check_consistency();
  EXPECT_EQ(pi.error, Error::kOk) << pi.reason;  // i2c.bus 1 (a Pi's header)
  ASSERT_EQ(s.set(Id::kI2cBus, -1).error, Error::kOk);
  const auto neither = s.check_consistency();
  EXPECT_EQ(neither.error, Error::kOutOfRange);
  EXPECT_NE(std::string_view(neither.reason).find("i2c.bus"), std::string_view::npos)
      << neither.reason;
  ASSERT_EQ(s.set(Id::kPinI2cSda, 0).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kPinI2cScl, 1).error, Error::kOk);
  const auto pico = s.check_consistency();
  EXPECT_EQ(pico.error, Error::kOk) << pico.reason;  // the Pico's pins
}

TEST(Settings, ConsistencyRulesSpanSettings) {
  Settings s;
  ASSERT_EQ(s.set(Id::kAzMinDeg, 100).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzMaxDeg, 50).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOutOfRange);
}

}  // namespace
}  // namespace rotord::settings
