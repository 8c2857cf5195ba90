// The wear odometer's record (docs/care.md): what a save writes reads back
// whole, and anything else is refused with a reason (the counts then start
// again from zero).
#include "care/odometer_record.hpp"

#include <gtest/gtest.h>

#include <string>

#include "care/start_ceiling.hpp"

namespace rotord::care {
namespace {

std::string encoded(const Odometer& o) {
  char buf[2048];
  const std::size_t n = encode_record(o, buf, sizeof buf);
  return std::string(buf, n);
}

TEST(OdometerRecord, WhatIsWrittenReadsBackWhole) {
  AxisWear az;
  az.starts = 4000000000u;
  az.reversals = 7;
  az.run_ms = 9000000000ull;  // past 32 bits: 104 days of running
  az.turned_deg = 123456;
  az.brake_cycles = 3;
  az.relay_switchings = 99;
  az.faults[static_cast<std::size_t>(AxisFault::kSensorStuck)] = 2;
  AxisWear el;
  el.starts = 1;
  Odometer o;
  o.restore(az, el, 1795000000);
  const std::string text = encoded(o);
  ASSERT_FALSE(text.empty());
  AxisWear az2;
  AxisWear el2;
  std::int64_t date = 0;
  const char* why = "";
  ASSERT_TRUE(decode_record(text, az2, el2, date, why)) << why;
  EXPECT_EQ(az2.starts, az.starts);
  EXPECT_EQ(az2.run_ms, az.run_ms);
  EXPECT_EQ(az2.turned_deg, az.turned_deg);
  EXPECT_EQ(az2.faults, az.faults);
  EXPECT_EQ(el2.starts, 1u);
  EXPECT_EQ(date, 1795000000);
  // Too small a buffer writes nothing rather than half a record.
  char small[64];
  EXPECT_EQ(encode_record(o, small, sizeof small), 0u);
}

TEST(OdometerRecord, ADamagedRecordIsRefusedWithItsReason) {
  Odometer o;
  const std::string good = encoded(o);
  const auto refused = [](const std::string& text) {
    AxisWear az;
    AxisWear el;
    std::int64_t date = 0;
    const char* why = "";
    return decode_record(text, az, el, date, why) ? std::string() : std::string(why);
  };
  EXPECT_EQ(refused(good), "");
  EXPECT_EQ(refused(good.substr(0, good.size() / 2)), "not a JSON object");
  EXPECT_EQ(refused(""), "not a JSON object");
  std::string bad = good;
  bad.replace(bad.find("\"format\":1"), 10, "\"format\":9");
  EXPECT_EQ(refused(bad), "a format this rotord does not know");
  bad = good;
  bad.replace(bad.find("\"az.starts\":0"), 13, "\"az.starts\":-3");
  EXPECT_EQ(refused(bad), "a count that is negative, fractional or not a number");
  bad = good;
  bad.replace(bad.find("\"az.starts\":0"), 13, "\"az.starts\":1.5");
  EXPECT_EQ(refused(bad), "a count that is negative, fractional or not a number");
  bad = good;
  bad.replace(bad.find("\"az.starts\":0"), 13, "\"az.starts\":\"x\"");
  EXPECT_EQ(refused(bad), "a count that is negative, fractional or not a number");
  bad = good;
  bad.replace(bad.find("\"az.starts\":0"), 13, "\"az.starts\":5000000000");
  EXPECT_EQ(refused(bad), "a count beyond 32 bits");
  bad = good;
  bad.replace(bad.find("\"az.starts\":0,"), 14, "");
  EXPECT_EQ(refused(bad), "counts missing");
  bad = good;
  bad.replace(bad.find("\"az.starts\""), 11, "\"az.startz\"");
  EXPECT_EQ(refused(bad), "an unknown key");
}

TEST(StartCeiling, NoHourHoldsMoreStartsThanTheCeiling) {
  // A start whenever allowed, for three hours: every sliding hour (checked
  // each minute) holds at most the ceiling.
  StartCeiling c;
  std::uint32_t starts = 0;
  std::vector<Millis> at;
  for (Millis now = 0; now < 3 * 3600000; now += 1000) {
    c.observe(starts, now, 30);
    if (c.allows_start(30)) {
      ++starts;
      at.push_back(now);
    }
  }
  c.observe(starts, 3 * 3600000, 30);
  for (Millis end = 3600000; end <= 3 * 3600000; end += 60000) {
    int in_hour = 0;
    for (const Millis t : at)
      if (t > end - 3600000 && t <= end) ++in_hour;
    EXPECT_LE(in_hour, 30) << "the hour ending at " << end / 60000 << " min";
  }
  // Spread out: the pace, not a burst of 30 and a wait of 58 minutes.
  EXPECT_GE(starts, 80u);
  EXPECT_TRUE(c.allows_start(0));  // 0: no ceiling
}

}  // namespace
}  // namespace rotord::care
