#pragma once
#include <string_view>

#include "axis/drive_outputs.hpp"
#include "sim/plant.hpp"
#include "sim/profiles.hpp"

namespace rotord::sim::test {

inline constexpr double kDt_s = 0.001;

/// Steps the plant for duration_s in 1 ms steps with the outputs held.
inline void run(AxisPlant& plant, const DriveOutputs& outputs, double duration_s) {
  const long steps = static_cast<long>(duration_s / kDt_s + 0.5);
  for (long n = 0; n < steps; ++n) plant.step(kDt_s, outputs);
}

inline DriveOutputs outputs_with(OutputChannel ch, float value = 1.0f) {
  DriveOutputs o;
  o.set(ch, value);
  return o;
}

inline const AxisProfile& profile_axis(std::string_view profile, bool el) {
  const Profile* p = find_profile(profile);
  return el ? p->el : p->az;
}

}  // namespace rotord::sim::test
