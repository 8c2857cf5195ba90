#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "settings/settings.hpp"

namespace rotord::settings {
namespace {

TEST(SettingsTable, EveryRowIsWellFormed) {
  for (std::size_t n = 0; n < kCount; ++n) {
    const Def& d = def(static_cast<Id>(n));
    SCOPED_TRACE(d.key);
    EXPECT_GT(std::strlen(d.key), 0u);
    EXPECT_GT(std::strlen(d.help), 0u);
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
