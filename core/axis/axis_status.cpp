#include "axis/axis_status.hpp"

namespace rotord {

const char* axis_state_name(AxisState state) {
  switch (state) {
    case AxisState::kIdle:
      return "IDLE";
    case AxisState::kStarting:
      return "STARTING";
    case AxisState::kMoving:
      return "MOVING";
    case AxisState::kStopping:
      return "STOPPING";
    case AxisState::kReversing:
      return "REVERSING";
    case AxisState::kFault:
      return "FAULT";
  }
  return "?";
}

const char* axis_fault_name(AxisFault fault) {
  switch (fault) {
    case AxisFault::kNone:
      return "NONE";
    case AxisFault::kStall:
      return "STALL";
    case AxisFault::kSensorLost:
      return "SENSOR_LOST";
    case AxisFault::kSensorRange:
      return "SENSOR_RANGE";
    case AxisFault::kSensorJump:
      return "SENSOR_JUMP";
    case AxisFault::kTimeout:
      return "TIMEOUT";
    case AxisFault::kNoSensor:
      return "NO_SENSOR";
    case AxisFault::kSensorStuck:
      return "SENSOR_STUCK";
    case AxisFault::kSlip:
      return "SLIP";
    case AxisFault::kEstop:
      return "ESTOP";
  }
  return "?";
}

}  // namespace rotord
