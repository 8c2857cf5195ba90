#pragma once
// Calibration in the command layer: the console's `cal <az|el> <lo|hi>` and
// GS-232's O / F / O2 / F2 call it, and it writes their one log line
// (docs/logging.md): "command cal az lo from console (USB): OK".
#include "command/command_log.hpp"
#include "rotator/controller.hpp"

namespace rotord::command {

/// The two calibration points: kLo with the rotator at its counter-clockwise
/// (down) stop (GS-232's O / O2, "offset"), kHi at its clockwise (up) stop
/// (F / F2, "full scale").
enum class CalPoint : std::uint8_t { kLo, kHi };

/// Where the real controller has the installer turn a trimmer until the reading
/// is right, rotord stores the sensor's present raw value as the calibration
/// point of that stop in the settings table, exactly as the web page's
/// "Set as low/high point" buttons do: pot sensors get
/// {az,el}.pot_cal_{lo,hi}_{counts,deg} = (raw now, az.min_deg / az.max_deg or
/// el.min_deg / el.max_deg, less the axis offset, which the axis adds back). MA3
/// encoders get {az,el}.ma3_zero_deg for the offset point; their full scale is
/// fixed, so F answers kNotSupported. Nothing changes when the result would
/// break a consistency rule (e.g. both points at the same counts): kOutOfRange.
/// kNotSupported also for an elevation the rotator does not have.
Error calibrate(Controller& controller, const Origin& from, AxisId axis, CalPoint point);

}  // namespace rotord::command
