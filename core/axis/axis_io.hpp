#pragma once
#include "axis/drive_outputs.hpp"
#include "hal/analog_in.hpp"
#include "hal/digital_in.hpp"
#include "hal/i2c.hpp"
#include "hal/pwm_in.hpp"

namespace rotord {

/// The hardware one axis is wired to. A port (or the simulator) fills it in;
/// null means "not fitted".
struct AxisIo {
  hal::AnalogIn* pot = nullptr;
  hal::PwmIn* ma3 = nullptr;
  hal::DigitalIn* limit_cw = nullptr;   ///< end switch in the CW / UP direction
  hal::DigitalIn* limit_ccw = nullptr;  ///< end switch in the CCW / DOWN direction
  hal::DigitalIn* t1 = nullptr;         ///< threshold: azimuth is in the CW overlap (> 360)
  hal::DigitalIn* t2 = nullptr;         ///< threshold: azimuth is in the CCW overlap (< 0)
  DriveSink* drive = nullptr;
  hal::DigitalIn* button_fwd = nullptr;  ///< manual push button CW / UP
  hal::DigitalIn* button_rev = nullptr;  ///< manual push button CCW / DOWN
  hal::I2c* i2c = nullptr;               ///< magnetometer bus (azimuth)
};

}  // namespace rotord
