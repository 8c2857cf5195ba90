#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rotord::linux_port {

/// Command-line options of rotord (see main.cpp for their help texts).
struct Options {
  std::string config_path;
  std::string hw = "sim";  ///< sim or gpiod
  std::string sim_profile = "g5500";
  double speedup = 1.0;
  std::string clock = "wall";  ///< wall, or manual: controller time moves only when told (tests)
  /// --utc-start: UTC at controller time 0 under --clock manual or --speedup
  /// (tracking tests); empty: the system clock at start.
  std::string utc_start;
  std::uint32_t sim_seed = 1;
  std::string bind = "0.0.0.0";
  int web_port = 8080;
  int rotctld_port = 4533;
  int wrc_port = 1234;
  int gs232_port = 4601;
  int easycomm_port = 4602;
  int seed_port = 0;
  std::vector<std::string> ptys;     ///< --pty PERSONALITY[:LINK]
  std::vector<std::string> serials;  ///< --serial PERSONALITY:DEVICE[:BAUD]
  std::string log_level = "info";    ///< error, warn, info or debug (log.hpp)
  std::string log_format = "text";   ///< text or json
};

}  // namespace rotord::linux_port
