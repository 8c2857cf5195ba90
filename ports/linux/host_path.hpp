#pragma once
// Where rotord finds a kernel interface (/sys/bus/iio/devices, /sys/class/pwm,
// /dev): the real place, or the one an environment variable names, so tests
// can point rotord at a fake tree in a temporary directory.
#include <cstdlib>
#include <string>

namespace rotord::linux_port {

inline std::string host_path(const char* variable, const char* real_path) {
  const char* env = std::getenv(variable);
  return env != nullptr && env[0] != '\0' ? env : real_path;
}

}  // namespace rotord::linux_port
