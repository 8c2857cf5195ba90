#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "settings/pin_rules.hpp"
#include "settings/settings.hpp"

namespace rotord::settings {
namespace {

TEST(PinRules, DefaultsAreTheIssueSixWiring) {
  const Settings s;
  EXPECT_EQ(s.i(Id::kPinAzCw), 5);
  EXPECT_EQ(s.i(Id::kPinAzCcw), 6);
  EXPECT_EQ(s.i(Id::kPinAzSpeed), 7);
  EXPECT_EQ(s.i(Id::kPinAzT1), 9);
  EXPECT_EQ(s.i(Id::kPinAzT2), 10);
  EXPECT_EQ(s.i(Id::kPinAzL1), 11);
  EXPECT_EQ(s.i(Id::kPinAzL2), 12);
  EXPECT_EQ(s.i(Id::kPinAzMa3), 2);
  EXPECT_EQ(s.i(Id::kPinAzPot), 26);
  EXPECT_EQ(s.i(Id::kPinElPot), 27);
  EXPECT_EQ(s.i(Id::kPinBtnCw), kNoPin);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(PinRules, EveryPinRowIsAGpioNumberThatNeedsARestart) {
  int pins = 0;
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    if (!is_pin(id)) continue;
    ++pins;
    SCOPED_TRACE(def(id).key);
    EXPECT_EQ(def(id).type, Type::kInt);
    EXPECT_EQ(def(id).min, kNoPin);
    EXPECT_EQ(def(id).max, 28);
    EXPECT_EQ(def(id).flags & kRestart, kRestart);
  }
  EXPECT_GE(pins, 27);
}

TEST(PinRules, TwoFunctionsOnOnePinAreRefusedNamingBoth) {
  Settings s;
  ASSERT_EQ(s.set(Id::kPinBtnCw, 2).error, Error::kOk);  // the MA3's default pin
  const Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_STREQ(r.reason, "pins.az_ma3 and pins.btn_cw both use GPIO 2");
  // Unwiring the encoder frees the pin.
  ASSERT_EQ(s.set(Id::kPinAzMa3, kNoPin).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(PinRules, UnwiredPinsNeverConflict) {
  Settings s;
  for (const Id id : {Id::kPinBtnCw, Id::kPinBtnCcw, Id::kPinBtnUp, Id::kPinBtnDown,
                      Id::kPinAzBrake, Id::kPinElSpeed})
    ASSERT_EQ(s.set(id, kNoPin).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(PinRules, WifiChipPinsAreRefused) {
  Settings s;
  ASSERT_EQ(s.set(Id::kPinAzBrake, 24).error, Error::kOk);
  const Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_NE(std::strstr(r.reason, "pins.az_brake"), nullptr);
  EXPECT_NE(std::strstr(r.reason, "Wi-Fi"), nullptr);
  EXPECT_EQ(s.set(Id::kPinAzBrake, 29).error, Error::kOutOfRange);  // beyond the table's range
}

TEST(PinRules, PotsNeedAnAdcPin) {
  Settings s;
  ASSERT_EQ(s.set(Id::kPinAzPot, 13).error, Error::kOk);
  const Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_NE(std::strstr(r.reason, "pins.az_pot"), nullptr);
  ASSERT_EQ(s.set(Id::kPinAzPot, 28).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(PinRules, I2cPinsMustBeOnePairOfOneBlock) {
  Settings s;
  ASSERT_EQ(s.set(Id::kPinI2cScl, 13).error, Error::kOk);  // I2C0 SCL is 1, 5, 9, 13...
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
  ASSERT_EQ(s.set(Id::kPinI2cScl, 4).error, Error::kOk);  // even: an SDA pin
  EXPECT_EQ(s.check_consistency().error, Error::kOutOfRange);
  ASSERT_EQ(s.set(Id::kPinI2cScl, 3 + 0).error, Error::kOk);  // I2C1 SCL, but SDA 0 is I2C0
  ASSERT_EQ(s.set(Id::kPinElMa3, kNoPin).error, Error::kOk);
  const Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_NE(std::strstr(r.reason, "pins.i2c_sda"), nullptr);
  ASSERT_EQ(s.set(Id::kPinI2cScl, kNoPin).error, Error::kOk);  // one of the two alone
  EXPECT_EQ(s.check_consistency().error, Error::kOutOfRange);
  ASSERT_EQ(s.set(Id::kPinI2cSda, kNoPin).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
}

TEST(PinRules, ACopyKeepsItsOwnReason) {
  Settings s;
  ASSERT_EQ(s.set(Id::kPinAzT1, 5).error, Error::kOk);
  const Rejection first = s.check_consistency();
  const std::string text = first.reason;
  Settings copy = s;
  ASSERT_EQ(copy.set(Id::kPinAzT1, 9).error, Error::kOk);
  EXPECT_EQ(copy.check_consistency().error, Error::kOk);
  EXPECT_EQ(text, first.reason);
  EXPECT_EQ(text, "pins.az_cw and pins.az_t1 both use GPIO 5");
}

}  // namespace
}  // namespace rotord::settings
