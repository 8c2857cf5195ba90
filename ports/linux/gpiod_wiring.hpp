#pragma once
// Which settings wire each axis of `rotord --hw gpiod`: shared by the
// daemon's GpiodRotator and `rotord --outputs-off`, so both drive the same
// lines and channels.
#include <optional>

#include "settings/settings.hpp"

namespace rotord::linux_port {

/// The settings of one axis's wiring.
struct AxisKeys {
  using Id = settings::Id;
  const char* name;
  Id drive, sensor;
  Id relay_fwd, relay_rev, speed;
  std::optional<Id> has_brake, brake;
  Id limit_cw, limit_ccw;
  std::optional<Id> t1, t2;
  Id ma3, button_fwd, button_rev;
  Id iio_device, iio_channel;
  Id pwm_fwd, pwm_rev;
};

inline constexpr AxisKeys kAzKeys{"az",
                                  settings::Id::kAzDrive,
                                  settings::Id::kAzSensor,
                                  settings::Id::kGpiodAzCw,
                                  settings::Id::kGpiodAzCcw,
                                  settings::Id::kGpiodAzSpeed,
                                  settings::Id::kAzHasBrake,
                                  settings::Id::kGpiodAzBrake,
                                  settings::Id::kGpiodAzL2,
                                  settings::Id::kGpiodAzL1,
                                  settings::Id::kGpiodAzT1,
                                  settings::Id::kGpiodAzT2,
                                  settings::Id::kGpiodAzMa3,
                                  settings::Id::kGpiodBtnCw,
                                  settings::Id::kGpiodBtnCcw,
                                  settings::Id::kIioAzDevice,
                                  settings::Id::kIioAzChannel,
                                  settings::Id::kPwmAzCw,
                                  settings::Id::kPwmAzCcw};

inline constexpr AxisKeys kElKeys{"el",
                                  settings::Id::kElDrive,
                                  settings::Id::kElSensor,
                                  settings::Id::kGpiodElUp,
                                  settings::Id::kGpiodElDown,
                                  settings::Id::kGpiodElSpeed,
                                  std::nullopt,
                                  std::nullopt,
                                  settings::Id::kGpiodElLimitUp,
                                  settings::Id::kGpiodElLimitDown,
                                  std::nullopt,
                                  std::nullopt,
                                  settings::Id::kGpiodElMa3,
                                  settings::Id::kGpiodBtnUp,
                                  settings::Id::kGpiodBtnDown,
                                  settings::Id::kIioElDevice,
                                  settings::Id::kIioElChannel,
                                  settings::Id::kPwmElUp,
                                  settings::Id::kPwmElDown};

}  // namespace rotord::linux_port
