#pragma once
#include "axis/drive_outputs.hpp"
#include "sim/plant_params.hpp"

namespace rotord::sim {

/// What the motor actually receives, after decoding the controller's output
/// channels for the drive kind. This is what goes through the relay delay line.
struct Actuation {
  bool powered = false;        ///< current flows in the motor
  double target_ratio = 0.0;   ///< steady speed w* / v_max, in [-1, 1]
  bool brake_released = true;  ///< false: the brake holds the axis

  bool operator==(const Actuation&) const = default;
};

/// Decodes one set of outputs (the plant model's first step, plant.hpp).
Actuation actuation_from(const AxisPlantParams& params, const DriveOutputs& outputs);

/// H-bridge dead band: w*/v_max = sign(d) max(0, (|d| - d0) / (1 - d0)).
double pwm_speed_ratio(double duty, double dead_band);

}  // namespace rotord::sim
