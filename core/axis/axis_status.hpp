#pragma once
#include <cstddef>
#include <cstdint>

#include "axis/drive_outputs.hpp"
#include "axis/sequencer.hpp"

namespace rotord {

enum class AxisState : std::uint8_t { kIdle, kStarting, kMoving, kStopping, kReversing, kFault };

/// Latched faults: the axis stops and stays stopped until a reset.
enum class AxisFault : std::uint8_t {
  kNone,
  kStall,        ///< driven but not moving
  kSensorLost,   ///< no signal from the position sensor
  kSensorRange,  ///< sensor reading outside its valid range
  kSensorJump,   ///< implausible jumps between readings
  kTimeout,      ///< a single move took too long
  kNoSensor,     ///< the configured sensor is not fitted
  kSensorStuck,  ///< the reading froze while the motor drove the axis at speed
  kSlip,         ///< moved at rest, outputs off (slip.fault on)
  kEstop,        ///< the emergency-stop input is (or was) active
};
/// Kinds of AxisFault, kNone included (kEstop must stay the last).
inline constexpr std::size_t kAxisFaultKinds = static_cast<std::size_t>(AxisFault::kEstop) + 1;
/// Kinds of AxisState (kFault must stay the last).
inline constexpr std::size_t kAxisStates = static_cast<std::size_t>(AxisState::kFault) + 1;

const char* axis_state_name(AxisState state);
const char* axis_fault_name(AxisFault fault);

/// A snapshot of one axis for protocols, the web page and tests (the
/// controller's working state doubles as telemetry).
struct AxisStatus {
  bool present = false;
  bool position_valid = false;
  float position_deg = 0.0f;  ///< unwrapped, offset applied
  float speed_deg_s = 0.0f;   ///< estimated from the sensor
  float raw = 0.0f;           ///< sensor raw value (ADC counts, encoder code)
  /// What `raw` spans, for calibration pages: the ADC's highest code for a
  /// pot, codes per turn for an MA3, 0 for a magnetometer (raw = heading).
  float raw_full_scale = 0.0f;
  float adc_ref_v = 0.0f;  ///< pot: ADC reference, volts = raw * adc_ref_v / raw_full_scale
  /// Magnetometer: the last raw field sample (chip counts) for the hard-iron
  /// calibration; mag_valid is false when the chip did not answer.
  bool mag_valid = false;
  std::int16_t mag_x = 0, mag_y = 0, mag_z = 0;
  bool has_target = false;
  float target_deg = 0.0f;
  bool jogging = false;
  bool arrived = false;  ///< the last go-to ended within tolerance
  AxisState state = AxisState::kIdle;
  Direction drive_dir = Direction::kNone;  ///< direction being driven (or stopping from)
  AxisFault fault = AxisFault::kNone;
  bool limit_cw = false;   ///< CW/UP blocked (switch or soft limit)
  bool limit_ccw = false;  ///< CCW/DOWN blocked
  bool switch_cw = false;  ///< raw limit switch inputs
  bool switch_ccw = false;
  bool t1 = false;
  bool t2 = false;
  float coast_s = 0.0f;     ///< learned coast time constant
  std::uint32_t moves = 0;  ///< motor starts since boot (relay wear, hunting checks)
  /// Sensor readings the robust filter turned away since boot (bursts,
  /// spikes): a sensor going bad shows here before it latches a fault.
  std::uint32_t readings_rejected = 0;
  /// Uncommanded motion at rest (slip.deg): events since boot, and whether
  /// one is going on now.
  std::uint32_t slips = 0;
  bool slipping = false;
  /// slip.rehold: go-tos back to the rest heading after a slip since boot,
  /// the heading of the last one, whether one goes on now, and the slips
  /// not re-held because the limit (Axis::kMaxReholds in
  /// Axis::kReholdWindowMs) was reached.
  std::uint32_t reholds = 0;
  float rehold_deg = 0.0f;
  bool reholding = false;
  std::uint32_t reholds_refused = 0;
  /// A go-to waits at rest, outside its tolerance, because the starts
  /// ceiling (care.max_starts_h) allows no start yet: its tolerance is
  /// widened to the distance it waits at.
  bool start_held = false;
  DriveOutputs outputs;
};

}  // namespace rotord
