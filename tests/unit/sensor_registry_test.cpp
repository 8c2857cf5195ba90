// The one list of sensor types (issue 25): a row a type, in the order of the
// stored *.sensor values, agreeing with the settings table's choices, each
// row fitting its sensor from its own input only.
#include "axis/sensor_registry.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "axis/axis_config.hpp"
#include "axis/axis_status.hpp"
#include "fake_rotator.hpp"
#include "settings/settings.hpp"

namespace rotord {
namespace {

using settings::Id;

TEST(SensorRegistry, OneRowPerTypeInTheOrderTheSettingsStore) {
  ASSERT_EQ(sensor_types().size(), kSensorTypeCount);
  std::set<std::string_view> keys;
  for (std::size_t n = 0; n < sensor_types().size(); ++n) {
    const SensorInfo& t = sensor_types()[n];
    EXPECT_EQ(static_cast<std::size_t>(t.type), n) << t.key;
    EXPECT_TRUE(keys.insert(t.key).second) << t.key;
    EXPECT_EQ(&sensor_info(t.type), &t);
    EXPECT_EQ(find_sensor(static_cast<int>(n)), &t);
    EXPECT_FALSE(t.name.empty());
  }
  EXPECT_EQ(find_sensor(-1), nullptr);
  EXPECT_EQ(find_sensor(static_cast<int>(kSensorTypeCount)), nullptr);
  // The values settings files store today, and the input each reads.
  EXPECT_EQ(sensor_info(SensorType::kPot).key, "pot");
  EXPECT_EQ(sensor_info(SensorType::kMa3).key, "ma3");
  EXPECT_EQ(sensor_info(SensorType::kMag).key, "mag");
  EXPECT_EQ(sensor_info(SensorType::kPot).input, SensorInput::kAnalog);
  EXPECT_EQ(sensor_info(SensorType::kMa3).input, SensorInput::kPwm);
  EXPECT_EQ(sensor_info(SensorType::kMag).input, SensorInput::kI2c);
}

/// az.sensor offers every row, by its key, at its value; el.sensor a first
/// part of the same list (a choice is its position), none of it a row kept
/// to the azimuth.
TEST(SensorRegistry, TheSettingsChoicesAreTheRowsKeys) {
  ASSERT_EQ(static_cast<std::size_t>(settings::choice_count(Id::kAzSensor)), kSensorTypeCount);
  const int el_choices = settings::choice_count(Id::kElSensor);
  EXPECT_GE(el_choices, 1);
  for (const SensorInfo& t : sensor_types()) {
    const int value = static_cast<int>(t.type);
    EXPECT_EQ(settings::choice_name(Id::kAzSensor, value), t.key);
    if (value >= el_choices) continue;
    EXPECT_EQ(settings::choice_name(Id::kElSensor, value), t.key);
    EXPECT_FALSE(t.azimuth_only) << t.key;
  }
  EXPECT_TRUE(sensor_info(SensorType::kMag).azimuth_only);
  EXPECT_EQ(el_choices, 2);  // pot, ma3: as stored today
}

class NoBus final : public hal::I2c {
 public:
  bool write(std::uint8_t, const std::uint8_t*, std::size_t) override { return false; }
  bool write_read(std::uint8_t, const std::uint8_t*, std::size_t, std::uint8_t*,
                  std::size_t) override {
    return false;
  }
};

/// A row builds its sensor from its own input and from nothing else: the
/// ports and the simulator fit inputs, the row picks its own.
TEST(SensorRegistry, EachRowFitsItsSensorFromItsOwnInputOnly) {
  testing::FakeAdc adc;
  testing::FakePwmIn pwm;
  NoBus bus;
  for (const SensorInfo& t : sensor_types()) {
    AxisIo only;  // just the row's input wired
    if (t.input == SensorInput::kAnalog) only.pot = &adc;
    if (t.input == SensorInput::kPwm) only.ma3 = &pwm;
    if (t.input == SensorInput::kI2c) only.i2c = &bus;
    SensorSlots slots;
    EXPECT_NE(t.fit(slots, only), nullptr) << t.key;
    SensorSlots none;
    AxisIo others{&adc, &pwm};
    others.i2c = &bus;
    if (t.input == SensorInput::kAnalog) others.pot = nullptr;
    if (t.input == SensorInput::kPwm) others.ma3 = nullptr;
    if (t.input == SensorInput::kI2c) others.i2c = nullptr;
    EXPECT_EQ(t.fit(none, others), nullptr) << t.key;
  }
}

/// The per-type behaviour the tracker used to switch on, now the rows':
/// the resolution the gate's floor uses, what counts as a recalibration,
/// and what the status says of the raw value.
TEST(SensorRegistry, RowsKeepTheTrackersPerTypeBehaviour) {
  AxisConfig c;
  c.pot_cal = PotCalibration::two_point(0.0f, 0.0f, 4500.0f, 450.0f);
  EXPECT_FLOAT_EQ(sensor_info(SensorType::kPot).resolution_deg(c), 0.1f);
  c.ma3_bits = 10;
  EXPECT_FLOAT_EQ(sensor_info(SensorType::kMa3).resolution_deg(c), 360.0f / 1024.0f);
  c.ma3_bits = 12;
  EXPECT_FLOAT_EQ(sensor_info(SensorType::kMa3).resolution_deg(c), 360.0f / 4096.0f);
  EXPECT_FLOAT_EQ(sensor_info(SensorType::kMag).resolution_deg(c), 0.1f);

  AxisConfig moved = c;
  moved.ma3_zero_deg = 12.0f;  // another type's calibration: not the pot's frame
  EXPECT_FALSE(sensor_info(SensorType::kPot).frame_changed(c, moved));
  EXPECT_TRUE(sensor_info(SensorType::kMa3).frame_changed(c, moved));
  EXPECT_FALSE(sensor_info(SensorType::kMag).frame_changed(c, moved));
  moved = c;
  moved.pot_cal = PotCalibration::two_point(10.0f, 0.0f, 4500.0f, 450.0f);
  EXPECT_TRUE(sensor_info(SensorType::kPot).frame_changed(c, moved));
  moved = c;
  moved.mag_chip = MagChip::kHmc5883l;
  EXPECT_TRUE(sensor_info(SensorType::kMag).frame_changed(c, moved));

  testing::FakeAdc adc;
  testing::FakePwmIn pwm;
  AxisIo io{&adc, &pwm};
  SensorSlots slots;
  AxisStatus st;
  sensor_info(SensorType::kPot).publish(slots, io, c, true, st);
  EXPECT_FLOAT_EQ(st.raw_full_scale, 8191.0f);
  EXPECT_FLOAT_EQ(st.adc_ref_v, 3.3f);
  st = AxisStatus{};
  sensor_info(SensorType::kMa3).publish(slots, io, c, true, st);
  EXPECT_FLOAT_EQ(st.raw_full_scale, 4096.0f);
  EXPECT_FALSE(st.mag_valid);
}

}  // namespace
}  // namespace rotord
