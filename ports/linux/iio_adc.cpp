#include "iio_adc.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string_view>

#include "host_path.hpp"

namespace rotord::linux_port {
namespace {

bool read_text(const std::string& path, std::string& out) {
  std::ifstream in(path);
  if (!in) return false;
  std::getline(in, out);
  return !in.bad();
}

bool parse_long(std::string_view text, long& out) {
  std::string s(text);
  char* end = nullptr;
  errno = 0;
  out = std::strtol(s.c_str(), &end, 10);
  return errno == 0 && end != s.c_str() && (*end == '\0' || *end == '\n');
}

}  // namespace

std::string iio_root() {
  return host_path("ROTORD_IIO_ROOT", "/sys/bus/iio/devices");
}

int iio_full_scale_for(const std::string& name) {
  // mcp320x registers each chip under its own name; raw codes are unsigned.
  // (ti-ads1015 registers every ADS1x15 as "ads1015", so those are told
  // apart by their scan element type instead: iio_full_scale_from_type.)
  static constexpr struct {
    std::string_view name;
    int full_scale;
  } kKnown[] = {{"mcp3001", 1023}, {"mcp3002", 1023}, {"mcp3004", 1023}, {"mcp3008", 1023},
                {"mcp3201", 4095}, {"mcp3202", 4095}, {"mcp3204", 4095}, {"mcp3208", 4095}};
  for (const auto& k : kKnown)
    if (k.name == name) return k.full_scale;
  return 0;
}

int iio_full_scale_from_type(const std::string& type) {
  // "le:s16/16>>0" (ADS1115), "be:s12/16>>4" (ADS1015): sign, then bits.
  const auto colon = type.find(':');
  if (colon == std::string::npos || colon + 2 >= type.size()) return 0;
  const char sign = type[colon + 1];
  const int bits = std::atoi(type.c_str() + colon + 2);
  if ((sign != 's' && sign != 'u') || bits < 2 || bits > 16) return 0;
  // A signed single-ended input uses the positive half.
  return sign == 's' ? (1 << (bits - 1)) - 1 : (1 << bits) - 1;
}

IioAdc::~IioAdc() {
  if (fd_ >= 0) ::close(fd_);
}

bool IioAdc::open(const std::string& root, int device, int channel, int full_scale_counts,
                  std::string& error) {
  const std::string dir = root + "/iio:device" + std::to_string(device);
  const std::string prefix = dir + "/in_voltage" + std::to_string(channel);
  raw_path_ = prefix + "_raw";
  fd_ = ::open(raw_path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    error = "cannot open " + raw_path_ + ": " + std::strerror(errno);
    if (errno == ENOENT)
      error += " (is the ADC's driver loaded? see docs/gpiod.md for the overlay)";
    return false;
  }
  std::string name, type;
  read_text(dir + "/name", name);
  int full_scale = full_scale_counts;
  if (full_scale <= 0 &&
      read_text(dir + "/scan_elements/in_voltage" + std::to_string(channel) + "_type", type))
    full_scale = iio_full_scale_from_type(type);
  if (full_scale <= 0) full_scale = iio_full_scale_for(name);
  full_scale_ = static_cast<std::uint16_t>(full_scale);
  if (full_scale_ == 0) {
    error = "unknown full scale of IIO ADC " + dir + " (name '" + name +
            "'); set iio.full_scale_counts";
    return false;
  }
  // Per-channel scale (ti-ads1015), else the one shared by every channel
  // (mcp320x). Only shown in the calibration page, so its absence is no error.
  std::string scale_text;
  if (read_text(prefix + "_scale", scale_text) || read_text(dir + "/in_voltage_scale", scale_text))
    reference_v_ =
        static_cast<float>(std::strtod(scale_text.c_str(), nullptr) * full_scale_ / 1000.0);
  if (!sample()) {
    error = last_error_;
    return false;
  }
  return true;
}

bool IioAdc::sample() {
  char buf[32];
  const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
  long value = 0;
  if (n <= 0) {
    last_error_ = "cannot read " + raw_path_ + ": " + (n < 0 ? std::strerror(errno) : "empty");
  } else if (buf[n] = '\0'; !parse_long(buf, value)) {
    last_error_ = raw_path_ + " holds no number";
  } else {
    // A single-ended ADS1x15 input can read a few codes below zero.
    if (value < 0) value = 0;
    if (value > full_scale_) value = full_scale_;
    counts_ = static_cast<std::uint16_t>(value);
    last_error_.clear();
    return true;
  }
  counts_ = 0;
  return false;
}

}  // namespace rotord::linux_port
