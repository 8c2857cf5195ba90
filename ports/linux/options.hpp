#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/protocol_registry.hpp"

namespace rotord::linux_port {

/// Command-line options of rotord (see main.cpp for their help texts).
struct Options {
  static std::array<int, protocol::kPersonalityCount> default_line_ports() {
    std::array<int, protocol::kPersonalityCount> ports{};
    for (const protocol::ProtocolInfo& p : protocol::protocols())
      ports[static_cast<std::size_t>(p.personality)] = p.tcp_by_default ? p.tcp_port : 0;
    return ports;
  }

  std::string config_path;
  std::string hw = "sim";  ///< sim or gpiod
  std::string sim_profile = "g5500";
  double speedup = 1.0;
  std::string clock = "wall";  ///< wall, or manual: controller time moves only when told (tests)
  /// --utc-start: UTC at controller time 0 under --clock manual or --speedup
  /// (tracking tests); empty: the system clock at start.
  std::string utc_start;
  std::uint32_t sim_seed = 1;
  /// --sim-sensor-mount: the simulated azimuth's MA3 and magnetometer read
  /// the antenna's bearing plus this (a sensor mounted off north).
  double sim_sensor_mount_deg = 0.0;
  /// "::": IPv6 and IPv4 on one socket per port (IPV6_V6ONLY off); on a
  /// host without IPv6 the daemon falls back to 0.0.0.0.
  std::string bind = "::";
  int web_port = 8080;
  /// --KEY-port of each line protocol, indexed by protocol::Personality;
  /// defaults from the protocol registry (0: off).
  std::array<int, protocol::kPersonalityCount> line_ports = default_line_ports();
  std::vector<std::string> ptys;     ///< --pty PERSONALITY[:LINK]
  std::vector<std::string> serials;  ///< --serial PERSONALITY:DEVICE[:BAUD]
  std::string log_level = "info";    ///< error, warn, info or debug (log.hpp)
  std::string log_format = "text";   ///< text or json
  std::string avahi = "on";          ///< on: announce through avahi-daemon (avahi_publisher.hpp)
};

}  // namespace rotord::linux_port
