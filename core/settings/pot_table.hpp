#pragma once
#include "sensors/pot_calibration.hpp"
#include "settings/settings.hpp"
#include "util/axis_id.hpp"

namespace rotord::settings {

/// The calibration table of one axis's pot from its rows: point 1
/// (*.pot_cal_lo_*), the *.pot_cal_mid_points extra points (*.pot_cal_m1_* ...)
/// and point 2 (*.pot_cal_hi_*), in that order.
PotCalibration pot_calibration_from(const Settings& s, AxisId axis);

/// The settings key of table point `index` (counts row), for error messages.
const char* pot_point_key(AxisId axis, int index, int count);

}  // namespace rotord::settings
