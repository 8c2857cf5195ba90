#pragma once
// H-bridge PWM through the kernel's PWM sysfs interface:
//   <root>/pwmchipN/export            write M to create pwmM
//   <root>/pwmchipN/pwmM/period       ns
//   <root>/pwmchipN/pwmM/duty_cycle   ns
//   <root>/pwmchipN/pwmM/enable       0 / 1
// The PWM block of the SoC makes the waveform, so the duty holds whatever
// the loop is doing; software PWM from a GPIO line would stretch a pulse
// each time rotord is late, which a motor turns into torque jumps. On a
// Raspberry Pi, `dtoverlay=pwm-2chan` gives pwmchip0 channels 0 and 1 on
// GPIO 18 and 19.
#include <cstdint>
#include <string>

#include "hal/pwm_out.hpp"

namespace rotord::linux_port {

/// The sysfs root of PWM chips; ROTORD_PWM_ROOT replaces it (for tests, which
/// point it at a fake tree in a temporary directory).
std::string pwm_root();

class SysfsPwm final : public hal::PwmOut {
 public:
  SysfsPwm() = default;
  /// Duty 0 and disabled; unexported if open() exported it.
  ~SysfsPwm() override;
  SysfsPwm(const SysfsPwm&) = delete;
  SysfsPwm& operator=(const SysfsPwm&) = delete;

  /// Exports the channel if needed, sets the period, duty 0 and enables it.
  /// False with `error` naming the file that is missing or refused.
  bool open(const std::string& root, int chip, int channel, int hz, std::string& error);
  /// Duty 0..1; writes duty_cycle only when it changes.
  void set_duty(float duty) override;
  const std::string& path() const { return dir_; }
  std::uint64_t period_ns() const { return period_ns_; }

 private:
  bool write_file(const std::string& name, const std::string& value, std::string& error) const;

  std::string chip_dir_;
  std::string dir_;
  int channel_ = -1;
  int duty_fd_ = -1;
  std::uint64_t period_ns_ = 0;
  std::uint64_t duty_ns_ = 0;
  bool exported_ = false;
  bool error_reported_ = false;
};

}  // namespace rotord::linux_port
