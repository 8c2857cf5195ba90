#pragma once
// A throw-away directory standing in for /sys/bus/iio/devices in tests.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace rotord::testing {

class FakeSysfs {
 public:
  FakeSysfs() {
    char pattern[] = "/tmp/rotord-iio-XXXXXX";
    root_ = ::mkdtemp(pattern);
  }
  ~FakeSysfs() {
    std::error_code ignored;
    std::filesystem::remove_all(root_, ignored);
  }
  FakeSysfs(const FakeSysfs&) = delete;
  FakeSysfs& operator=(const FakeSysfs&) = delete;

  const std::string& root() const { return root_; }
  /// Writes <root>/<relative> (directories created), replacing its content
  /// in place as sysfs does (an open descriptor sees the new value).
  void write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path path = root_ + "/" + relative;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::trunc) << text;
  }
  void remove(const std::string& relative) const {
    std::filesystem::remove(root_ + "/" + relative);
  }

  /// An ADS1115 as the ti-ads1015 driver shows it: every ADS1x15 is named
  /// "ads1015"; the scan element type tells 16 bits from 12.
  void add_ads1115(int device, int channel, int raw) const {
    const std::string dir = "iio:device" + std::to_string(device) + "/";
    write(dir + "name", "ads1015\n");
    write(dir + "in_voltage" + std::to_string(channel) + "_raw", std::to_string(raw) + "\n");
    write(dir + "in_voltage" + std::to_string(channel) + "_scale", "0.125000000\n");
    write(dir + "scan_elements/in_voltage" + std::to_string(channel) + "_type", "le:s16/16>>0\n");
  }

 private:
  std::string root_;
};

}  // namespace rotord::testing
