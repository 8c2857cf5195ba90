// The settings as main had them before the per-axis rows were declared once
// (issue 25): the table row for row, and settings files main's daemon wrote,
// read into the same values and the same AxisConfig of each axis. The files
// are tests/data/settings/ (README.md there says how they were made),
// compiled in so that the Cortex-M0+ reads them too.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "axis/axis_config.hpp"
#include "json/settings_json.hpp"
#include "json_members.hpp"
#include "memory_storage.hpp"
#include "settings/axis_rows.hpp"
#include "settings/settings.hpp"
#include "string_sink.hpp"

extern const char kMainSettingsTable[];
extern const unsigned long kMainSettingsTable_size;
extern const char kMainEveryKeyJson[];
extern const unsigned long kMainEveryKeyJson_size;
extern const char kMainEveryKeyApiSettings[];
extern const unsigned long kMainEveryKeyApiSettings_size;
extern const char kMainAxesApartJson[];
extern const unsigned long kMainAxesApartJson_size;

namespace rotord::settings {
namespace {

/// One line of main_table.txt: "key|type=..|flags=..|unit=..|min=..|max=..|
/// default=..|group=..|choices=..|label=..|when=..". Read by its field names
/// in order, since choices and conditions hold '|' themselves.
struct TableLine {
  std::string_view fields[11];
  bool read(std::string_view line) {
    static constexpr const char* kNames[] = {
        "|type=",    "|flags=", "|unit=",    "|min=",   "|max=",
        "|default=", "|group=", "|choices=", "|label=", "|when="};
    std::size_t start = 0;
    for (std::size_t n = 0; n < 10; ++n) {
      const std::size_t at = line.find(kNames[n], start);
      if (at == std::string_view::npos) return false;
      fields[n] = line.substr(start, at - start);
      start = at + std::strlen(kNames[n]);
    }
    fields[10] = line.substr(start);
    return true;
  }
  double number(std::size_t n) const {
    return std::strtod(std::string(fields[n]).c_str(), nullptr);
  }
};

// Main's rows in main's order, each column as it was; a row added since may
// sit between them.
TEST(SettingsOfMain, EveryRowOfMainIsHereUnchangedAndInOrder) {
  std::string_view rest(kMainSettingsTable, kMainSettingsTable_size);
  std::size_t rows = 0;
  int previous = -1;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    TableLine main;
    ASSERT_TRUE(main.read(line)) << line;
    ++rows;
    SCOPED_TRACE(line);
    const std::optional<Id> id = find(main.fields[0]);
    ASSERT_TRUE(id.has_value()) << "a key of main is gone";
    EXPECT_GT(static_cast<int>(*id), previous) << "out of main's order";
    previous = static_cast<int>(*id);
    const Def& d = def(*id);
    EXPECT_EQ(main.number(1), static_cast<int>(d.type));
    EXPECT_EQ(main.number(2), d.flags);
    EXPECT_EQ(main.fields[3], d.unit);
    EXPECT_EQ(main.number(4), d.min);
    EXPECT_EQ(main.number(5), d.max);
    EXPECT_EQ(main.number(6), d.default_value);
    EXPECT_EQ(main.fields[7], d.group);
    EXPECT_EQ(main.fields[8], d.choices);
    EXPECT_EQ(main.fields[9], d.label);
    EXPECT_EQ(main.fields[10], condition(*id));
  }
  EXPECT_EQ(rows, 268u) << "main had 268 rows";
}

/// Loads a file main's daemon wrote over the table's defaults.
web::LoadOutcome load(const char* text, unsigned long size, Settings& out) {
  testing::MemoryStorage storage;
  storage.has_document = true;
  storage.document.assign(text, size);
  static Settings scratch;
  static char buf[web::kMaxSettingsDocumentBytes];
  web::LoadReport report;
  const web::LoadOutcome outcome =
      web::load_settings(storage, Settings(), nullptr, out, scratch, buf, sizeof buf, &report);
  EXPECT_TRUE(report.empty()) << (report.size() > 0 ? report[0].key : "") << ": "
                              << (report.size() > 0 ? report[0].reason : "");
  return outcome;
}

TEST(SettingsOfMain, AFileWithEveryKeyChangedReadsAsMainReadIt) {
  static Settings s;
  const web::LoadOutcome outcome = load(kMainEveryKeyJson, kMainEveryKeyJson_size, s);
  EXPECT_EQ(outcome.status, web::LoadOutcome::kLoaded) << outcome.key << ": " << outcome.reason;
  EXPECT_FALSE(outcome.access_unreadable);
  // Every key is in the file, so the base does not matter: each value as
  // GET /api/settings of main's daemon on this file gave it, byte for byte.
  testing::StringSink sink;
  {
    web::JsonWriter w(sink);
    web::write_settings(s, w);
  }
  EXPECT_EQ(
      testing::missing_or_changed(
          std::string_view(kMainEveryKeyApiSettings, kMainEveryKeyApiSettings_size), sink.data),
      "");
}

TEST(SettingsOfMain, EveryPerAxisValueOfMainsFileArrivesInAxisConfig) {
  static Settings s;
  load(kMainEveryKeyJson, kMainEveryKeyJson_size, s);
  const AxisConfig az = axis_config_from(s, AxisId::kAz);
  const AxisConfig el = axis_config_from(s, AxisId::kEl);
  // Values as the file has them (main_every_key.json), each axis its own.
  EXPECT_FLOAT_EQ(az.min_deg, -15.5f);
  EXPECT_FLOAT_EQ(el.min_deg, -2.5f);
  EXPECT_FLOAT_EQ(az.max_deg, 455.25f);
  EXPECT_FLOAT_EQ(el.max_deg, 178.75f);
  EXPECT_TRUE(az.continuous);
  EXPECT_FLOAT_EQ(az.offset_deg, 0.27f);
  EXPECT_FLOAT_EQ(el.offset_deg, 0.01f);
  EXPECT_FLOAT_EQ(az.tolerance_deg, 1.28f);
  EXPECT_FLOAT_EQ(el.tolerance_deg, 1.02f);
  EXPECT_FLOAT_EQ(az.slow_zone_deg, 10.29f);
  EXPECT_FLOAT_EQ(el.slow_zone_deg, 5.03f);
  EXPECT_EQ(az.drive, DriveType::kHBridge);
  EXPECT_EQ(el.drive, DriveType::kHBridge);
  EXPECT_TRUE(az.has_brake);
  EXPECT_EQ(az.brake_release_ms, 510);
  EXPECT_EQ(az.brake_engage_ms, 3011);
  EXPECT_EQ(az.dir_settle_ms, 51);
  EXPECT_EQ(el.dir_settle_ms, 52);
  EXPECT_EQ(az.soft_ms, 2);
  EXPECT_EQ(el.soft_ms, 3);
  EXPECT_EQ(az.reverse_dead_ms, 1003);
  EXPECT_EQ(el.reverse_dead_ms, 1004);
  EXPECT_EQ(az.min_dwell_ms, 304);
  EXPECT_EQ(el.min_dwell_ms, 305);
  EXPECT_FLOAT_EQ(az.pwm_slow_duty, 0.41f);
  EXPECT_FLOAT_EQ(el.pwm_slow_duty, 0.52f);
  EXPECT_FLOAT_EQ(az.pwm_fast_duty, 0.93f);
  EXPECT_FLOAT_EQ(el.pwm_fast_duty, 0.88f);
  EXPECT_EQ(az.sensor, SensorType::kMag);
  EXPECT_EQ(el.sensor, SensorType::kMa3);
  // Point 1, the extra points in order, point 2.
  const float az_points[][2] = {{101.5f, -14.5f}, {601, 50.5f},      {1102, 111.25f},
                                {1603, 172},      {2104, 233.75f},   {2605, 294.5f},
                                {3106, 355.25f},  {3701.25f, 451.5f}};
  ASSERT_EQ(az.pot_cal.count, 8);
  for (int n = 0; n < 8; ++n) {
    EXPECT_FLOAT_EQ(az.pot_cal.points[n].counts, az_points[n][0]) << n;
    EXPECT_FLOAT_EQ(az.pot_cal.points[n].deg, az_points[n][1]) << n;
  }
  // Five of the six extra points in use: the sixth (600, 150.25) is not.
  const float el_points[][2] = {{3650.5f, -1.5f}, {3100, 20.5f},  {2600, 45.25f},   {2100, 70},
                                {1600, 95.75f},   {1100, 120.5f}, {120.25f, 177.5f}};
  ASSERT_EQ(el.pot_cal.count, 7);
  for (int n = 0; n < 7; ++n) {
    EXPECT_FLOAT_EQ(el.pot_cal.points[n].counts, el_points[n][0]) << n;
    EXPECT_FLOAT_EQ(el.pot_cal.points[n].deg, el_points[n][1]) << n;
  }
  EXPECT_FLOAT_EQ(s.f(Id::kElPotCalM6Counts), 600.0f);
  EXPECT_FLOAT_EQ(s.f(Id::kElPotCalM6Deg), 150.25f);
  EXPECT_EQ(az.pot_filter.samples, 11);
  EXPECT_EQ(el.pot_filter.samples, 12);
  EXPECT_FALSE(az.pot_filter.median);
  EXPECT_FALSE(el.pot_filter.median);
  EXPECT_EQ(az.pot_filter.lowpass_ms, 5);
  EXPECT_EQ(el.pot_filter.lowpass_ms, 6);
  EXPECT_FLOAT_EQ(az.ma3_zero_deg, 0.24f);
  EXPECT_FLOAT_EQ(el.ma3_zero_deg, 0.32f);
  EXPECT_TRUE(az.ma3_reverse);
  EXPECT_TRUE(el.ma3_reverse);
  EXPECT_EQ(az.ma3_bits, 10);
  EXPECT_EQ(el.ma3_bits, 10);
  EXPECT_EQ(az.mag_chip, MagChip::kHmc5883l);
  EXPECT_EQ(az.mag_cal, (MagCalibration{-1234, 1111, -987, 1321, 0.12f, true}));
  EXPECT_EQ(az.mag_lowpass_ms, 104);
  EXPECT_FLOAT_EQ(az.stall_deg, 2.27f);
  EXPECT_FLOAT_EQ(el.stall_deg, 2.35f);
  EXPECT_EQ(az.stall_ms, 3010);
  EXPECT_EQ(el.stall_ms, 3011);
  EXPECT_FLOAT_EQ(az.jump_deg, 15.29f);
  EXPECT_FLOAT_EQ(el.jump_deg, 15.37f);
  EXPECT_EQ(az.move_timeout_ms, 181000);
  EXPECT_EQ(el.move_timeout_ms, 182000);
  EXPECT_FLOAT_EQ(az.speed_deg_s, 6.31f);
  EXPECT_FLOAT_EQ(el.speed_deg_s, 2.72f);
  EXPECT_FLOAT_EQ(az.slow_speed_ratio, 0.62f);
  EXPECT_FLOAT_EQ(el.slow_speed_ratio, 0.33f);
  EXPECT_FLOAT_EQ(az.pwm_dead_band, 0.63f);
  EXPECT_FLOAT_EQ(el.pwm_dead_band, 0.34f);
  EXPECT_FLOAT_EQ(az.coast_s, 0.49f);
  EXPECT_FLOAT_EQ(el.coast_s, 0.15f);
  EXPECT_FALSE(az.coast_learn);
  EXPECT_FALSE(el.coast_learn);
  for (const AxisConfig* c : {&az, &el}) {  // the slip rows are both axes'
    EXPECT_FLOAT_EQ(c->slip_deg, 2.06f);
    EXPECT_TRUE(c->slip_fault);
    EXPECT_TRUE(c->slip_rehold);
  }
  // An elevation axis has no brake, no endless turning and no magnetometer.
  EXPECT_FALSE(el.continuous);
  EXPECT_FALSE(el.has_brake);
  EXPECT_EQ(el.brake_release_ms, 0);
  EXPECT_EQ(el.mag_lowpass_ms, 0);
}

// A switch changed on one axis only: with every key changed above, both
// axes hold the same non-default switch, so there each could be read from
// the other's row unnoticed. Here they differ.
TEST(SettingsOfMain, ASwitchChangedOnOneAxisArrivesOnThatAxisOnly) {
  static Settings s;
  EXPECT_EQ(load(kMainAxesApartJson, kMainAxesApartJson_size, s).status, web::LoadOutcome::kLoaded);
  const AxisConfig az = axis_config_from(s, AxisId::kAz);
  const AxisConfig el = axis_config_from(s, AxisId::kEl);
  EXPECT_EQ(az.drive, DriveType::kRelayVoltageSelect);
  EXPECT_EQ(el.drive, DriveType::kRelayTwoSpeed);
  EXPECT_EQ(az.sensor, SensorType::kMa3);
  EXPECT_EQ(el.sensor, SensorType::kPot);
  EXPECT_TRUE(az.ma3_reverse);
  EXPECT_FALSE(el.ma3_reverse);
  EXPECT_EQ(az.ma3_bits, 10);
  EXPECT_EQ(el.ma3_bits, 12);
  EXPECT_TRUE(az.pot_filter.median);
  EXPECT_FALSE(el.pot_filter.median);
  EXPECT_TRUE(az.coast_learn);
  EXPECT_FALSE(el.coast_learn);
}

// The one mapping from a per-axis row to its keys (axis_rows.hpp).
TEST(SettingsOfMain, EachPerAxisRowNamesItsAzAndElKeys) {
  for (std::size_t n = 0; n < kAxisRowCount; ++n) {
    const auto row = static_cast<AxisRow>(n);
    const std::string az = def(axis_id(AxisId::kAz, row)).key;
    const std::string el = def(axis_id(AxisId::kEl, row)).key;
    ASSERT_EQ(az.rfind("az.", 0), 0u) << az;
    EXPECT_EQ(el, "el." + az.substr(3));
  }
  EXPECT_EQ(axis_id(AxisId::kAz, AxisRow::kMinDeg), Id::kAzMinDeg);
  EXPECT_EQ(axis_id(AxisId::kEl, AxisRow::kCoastLearn), Id::kElCoastLearn);
  EXPECT_EQ(axis_id(AxisId::kAz, AxisRow::kDirSettleMs), Id::kAzDirSettleMs);
}

// The comparison above reads members, so it must split where JSON does.
TEST(SettingsOfMain, MembersSplitAtTheTopLevelCommasOnly) {
  const auto members = testing::json_members(R"({"a":"x,\"y","b":[1,2],"c":{"d":1,"e":2}})");
  ASSERT_EQ(members.size(), 3u);
  EXPECT_EQ(members[0], R"("a":"x,\"y")");
  EXPECT_EQ(members[1], R"("b":[1,2])");
  EXPECT_EQ(members[2], R"("c":{"d":1,"e":2})");
  EXPECT_EQ(testing::missing_or_changed(R"({"a":1,"c":3})", R"({"a":1,"b":2,"c":3})"), "");
  EXPECT_EQ(testing::missing_or_changed(R"({"a":1,"c":3})", R"({"c":3,"a":1})"), R"("c":3)");
  EXPECT_EQ(testing::missing_or_changed(R"({"a":1})", R"({"a":2})"), R"("a":1)");
  EXPECT_EQ(testing::missing_or_changed("{}", R"({"a":2})"), "(no members)");
}

}  // namespace
}  // namespace rotord::settings
