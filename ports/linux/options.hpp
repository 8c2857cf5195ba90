#pragma once
#include <cstdint>
#include <string>

namespace rotord::linux_port {

/// Command-line options of rotord (see main.cpp for their help texts).
struct Options {
  std::string config_path;
  std::string sim_profile = "g5500";
  double speedup = 1.0;
  std::uint32_t seed = 1;
  std::string bind = "0.0.0.0";
  int web_port = 8080;
  int rotctld_port = 4533;
  int wrc_port = 1234;
  int gs232_port = 4601;
  int easycomm_port = 4602;
};

}  // namespace rotord::linux_port
