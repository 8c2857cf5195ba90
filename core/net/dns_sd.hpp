#pragma once
// What rotord announces on the local network through DNS-SD (mDNS on the
// Pico W, Avahi on Linux), the same on every port: the web UI as
// _http._tcp, and Hamlib rotctld as _rotctld._tcp whose TXT records name the
// version and every other protocol's port, so a program that browses the
// network finds the WRC, GS-232, Easycomm and seed ports from one record.
// Which protocol is the service and which the TXT record names is a column
// of the protocol registry (protocol::announced_ports fills this).
#include <array>
#include <cstddef>
#include <cstdint>

namespace rotord::net {

/// The TCP ports rotord serves; 0: that protocol is off (not announced).
struct ServicePorts {
  /// Another protocol the _rotctld._tcp TXT record names: "key=port".
  struct Other {
    const char* key = nullptr;
    std::uint16_t port = 0;
  };
  static constexpr std::size_t kMaxOthers = 4;

  std::uint16_t web = 0;
  std::uint16_t rotctld = 0;  ///< the _rotctld._tcp service's own port
  std::array<Other, kMaxOthers> others{};
  std::size_t other_count = 0;

  /// Adds one to the TXT record, in order; beyond kMaxOthers, nothing.
  void add_other(const char* key, std::uint16_t port) {
    if (other_count < kMaxOthers) others[other_count++] = Other{key, port};
  }
};

/// Service types, as lwIP's responder takes them (name and protocol apart)
/// and as Avahi does ("_http._tcp").
inline constexpr const char* kHttpService = "_http";
inline constexpr const char* kRotctldService = "_rotctld";
inline constexpr const char* kHttpServiceType = "_http._tcp";
inline constexpr const char* kRotctldServiceType = "_rotctld._tcp";
/// The _http._tcp TXT record (RFC 6763 section 7's "path" key for HTTP).
inline constexpr const char* kHttpTxt = "path=/";

/// The TXT records of the _rotctld._tcp service, in order: "txtvers=1",
/// "version=0.1.0", then "web=" and each other protocol's "key=" (today
/// "wrc=", "gs232=", "easycomm=", "seed=") with the port of each that is on.
/// Fixed storage, no heap.
class RotctldTxt {
 public:
  static constexpr std::size_t kMaxRecords = 3 + ServicePorts::kMaxOthers;
  static constexpr std::size_t kMaxRecordBytes = 32;  ///< with the NUL

  RotctldTxt(const ServicePorts& ports, const char* version);
  std::size_t size() const { return count_; }
  /// Record `n` (< size()), NUL-terminated, "key=value".
  const char* operator[](std::size_t n) const { return records_[n]; }

 private:
  void add(const char* key, const char* value);
  void add_port(const char* key, std::uint16_t port);

  char records_[kMaxRecords][kMaxRecordBytes] = {};
  std::size_t count_ = 0;
};

}  // namespace rotord::net
