#pragma once
#include <array>
#include <cstdint>

namespace rotord {

/// The logical outputs of one axis. A port maps them onto pins (relays, PWM
/// slices); the simulator reads them as the motor's inputs. Which ones a
/// rotator uses depends on its drive type.
enum class OutputChannel : std::uint8_t {
  kRelayCw,      ///< direction relay CW (azimuth) / UP (elevation)
  kRelayCcw,     ///< direction relay CCW / DOWN
  kSpeedFast,    ///< two-speed relay drive: energised = fast
  kBrake,        ///< brake solenoid: energised = brake released
  kVoltageFast,  ///< voltage-select relay: energised = fast supply, off = creep
  kPwmCw,        ///< H-bridge duty for CW / UP, 0..1
  kPwmCcw,       ///< H-bridge duty for CCW / DOWN, 0..1
  kCount
};

inline constexpr std::size_t kOutputChannelCount = static_cast<std::size_t>(OutputChannel::kCount);

/// The channels' names in the REST status, the metrics and the logs.
inline constexpr const char* kOutputChannelNames[kOutputChannelCount] = {
    "relay_cw", "relay_ccw", "speed_fast", "brake", "voltage_fast", "pwm_cw", "pwm_ccw"};

struct DriveOutputs {
  std::array<float, kOutputChannelCount> value{};  // relays 0 or 1, PWM duty 0..1

  float get(OutputChannel ch) const { return value[static_cast<std::size_t>(ch)]; }
  void set(OutputChannel ch, float v) { value[static_cast<std::size_t>(ch)] = v; }
  bool on(OutputChannel ch) const { return get(ch) > 0.0f; }
  void all_off() { value.fill(0.0f); }
  bool any_on() const {
    for (float v : value)
      if (v > 0.0f) return true;
    return false;
  }
};

/// Where an axis writes its outputs once per tick.
class DriveSink {
 public:
  virtual ~DriveSink() = default;
  virtual void apply(const DriveOutputs& outputs) = 0;
};

}  // namespace rotord
