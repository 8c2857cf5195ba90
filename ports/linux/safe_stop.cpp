#include "safe_stop.hpp"

#include <cstdio>

namespace rotord::linux_port {

void stop_motors(Controller* controller, GpiodRotator* gpio) {
  if (controller != nullptr) {
    controller->stop();
    controller->shutdown();
  }
  if (gpio != nullptr) gpio->all_off();
}

namespace {

void describe_axis(std::string& out, const char* name, const DriveOutputs& o) {
  out += name;
  if (!o.any_on()) {
    out += " off";
    return;
  }
  for (std::size_t n = 0; n < kOutputChannelCount; ++n) {
    if (o.value[n] <= 0.0f) continue;
    char text[48];
    std::snprintf(text, sizeof text, " %s=%g", kOutputChannelNames[n],
                  static_cast<double>(o.value[n]));
    out += text;
  }
}

}  // namespace

std::string describe_outputs(const DriveOutputs& az, const DriveOutputs* el) {
  std::string out;
  describe_axis(out, "az", az);
  if (el != nullptr) {
    out += ", ";
    describe_axis(out, "el", *el);
  }
  return out;
}

}  // namespace rotord::linux_port
