#pragma once
#include "rotator/controller.hpp"

namespace rotord::protocol::gs232 {

/// The two calibration points of a GS-232: O / O2 ("offset") with the rotator
/// preset to its counter-clockwise (down) stop, F / F2 ("full scale") at its
/// clockwise (up) stop.
enum class CalPoint : std::uint8_t { kOffset, kFullScale };

/// Where the real controller has the installer turn a trimmer until the reading
/// is right, rotord stores the sensor's present raw value as the calibration
/// point of that stop in the settings table, exactly as the web page's
/// "Set as low/high point" buttons do: pot sensors get
/// {az,el}.pot_cal_{lo,hi}_{counts,deg} = (raw now, az.min_deg / az.max_deg or
/// el.min_deg / el.max_deg, less the axis offset, which the axis adds back). MA3
/// encoders get {az,el}.ma3_zero_deg for the offset point; their full scale is
/// fixed, so F answers kNotSupported. Nothing changes when the result would
/// break a consistency rule (e.g. both points at the same counts): kOutOfRange.
Error calibrate(Controller& controller, AxisId axis, CalPoint point);

}  // namespace rotord::protocol::gs232
