#pragma once
// The MQTT boundary of the command layer's tests: keeps the last result
// message the bridge published (<prefix>/result).
#include <string>
#include <string_view>

#include "mqtt/bridge.hpp"

namespace rotord::testing {

class LastResult final : public mqtt::Transport {
 public:
  std::string result;
  bool connected() const override { return true; }
  bool publish(std::string_view topic, std::string_view payload, bool) override {
    if (topic.ends_with("/result")) result = std::string(payload);
    return true;
  }
};

}  // namespace rotord::testing
