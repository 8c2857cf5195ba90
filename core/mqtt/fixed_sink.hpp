#pragma once
// The MQTT bridge's name for the core's fixed-buffer sink (util/fixed_sink.hpp).
#include "util/fixed_sink.hpp"

namespace rotord::mqtt {

using rotord::FixedSink;

}  // namespace rotord::mqtt
