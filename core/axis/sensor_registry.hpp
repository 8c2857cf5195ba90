#pragma once
// The one list of position sensor types: what `az.sensor` / `el.sensor`
// store, what each type reads (the input a port or the simulator fits for
// it) and how the position tracker configures, reads and reports it. The
// tracker, the simulator (sim/sim_rotator.cpp) and both ports
// (ports/linux/gpiod_io.cpp, ports/pico_w/main.cpp) find a type's behaviour
// here; none of them names a sensor type. docs/architecture.md, "Adding a
// sensor type", walks through one.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "axis/axis_io.hpp"
#include "sensors/ma3_sensor.hpp"
#include "sensors/mag_sensor.hpp"
#include "sensors/pot_sensor.hpp"

namespace rotord {

struct AxisConfig;
struct AxisStatus;

/// The sensor types, one value a row below (kSensorTypes), in its order.
/// The value is what the settings store (the *.sensor choice index): a
/// type's number never changes.
enum class SensorType : std::uint8_t { kPot, kMa3, kMag };
inline constexpr std::size_t kSensorTypeCount = 3;

/// The hardware input a type reads, one AxisIo member each. A port and the
/// simulator fit inputs by this column, never by type: a new type on an
/// input they already fit needs nothing from them.
enum class SensorInput : std::uint8_t {
  kAnalog,  ///< an ADC channel (AxisIo::pot; pins.*_pot, iio.*)
  kPwm,     ///< a PWM period input (AxisIo::ma3; pins.*_ma3, gpiod.*_ma3)
  kI2c,     ///< the azimuth's I2C bus (AxisIo::i2c; pins.i2c_*, i2c.bus)
};

/// Every sensor an axis has built, one slot a type (no heap: fixed members,
/// built only for a type whose input is wired).
struct SensorSlots {
  std::optional<PotSensor> pot;
  std::optional<Ma3Sensor> ma3;
  std::optional<MagSensor> mag;
};

struct SensorInfo {
  SensorType type;
  /// The *.sensor choice as the settings table stores and shows it
  /// ("pot|ma3|mag"; tests/unit/sensor_registry_test.cpp checks the two agree).
  std::string_view key;
  std::string_view name;  ///< for logs ("pot /sys/...", "MA3 on line 5")
  /// What `AxisStatus::raw` counts, as /api/status names it.
  std::string_view raw_unit;
  SensorInput input;
  /// Only the azimuth may use it (the one I2C bus): el.sensor's choices
  /// are the other rows.
  bool azimuth_only;
  /// Builds the sensor in `slots` when `io` has its input wired, and
  /// returns it; nullptr when the input is not wired.
  PositionSensor* (*fit)(SensorSlots& slots, const AxisIo& io);
  /// Hands the sensor its part of the axis configuration (its settings:
  /// calibration, filters, chip).
  void (*configure)(SensorSlots& slots, const AxisConfig& c);
  /// Whether the sensor's calibration differs between `a` and `b`: the same
  /// shaft position then reads as another angle, in one step.
  bool (*frame_changed)(const AxisConfig& a, const AxisConfig& b);
  /// The finest step the sensor resolves under `c`, degrees.
  float (*resolution_deg)(const AxisConfig& c);
  /// The type's own status fields (what `raw` spans, the raw field
  /// sample); `answered`: the last read got a sample, however implausible.
  void (*publish)(const SensorSlots& slots, const AxisIo& io, const AxisConfig& c, bool answered,
                  AxisStatus& status);
};

/// Every sensor type, in the order of SensorType.
std::span<const SensorInfo> sensor_types();
const SensorInfo& sensor_info(SensorType type);
/// The row of a stored *.sensor value, or nullptr for a value no row has.
/// (No lookup by key: the settings table turns a key into its value, and
/// the M0+'s flash budget has no room for an unused one.)
const SensorInfo* find_sensor(int stored);

}  // namespace rotord
