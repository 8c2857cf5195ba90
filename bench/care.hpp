#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// A day unattended (docs/care.md): 24 h of virtual time on each profile,
/// a go-to every 10 minutes, the sensor noise the profile sets, wind that
/// loads the motor while it turns and twists the mast at rest by less than
/// slip.deg. Counts the false alarms: slips, sensor faults, any fault, and
/// the readings the filter turned away. Each should be 0.
std::vector<Result> run_care_day();

}  // namespace rotord::bench
