#pragma once
#include "json/json_writer.hpp"

namespace rotord::web {

/// GET /api/station's document: the rotords a port sees on the station's
/// MQTT broker (mqtt/station.hpp). Not set: the endpoint answers 404.
class StationSource {
 public:
  virtual ~StationSource() = default;
  virtual void write_station(JsonWriter& w) const = 0;
};

}  // namespace rotord::web
