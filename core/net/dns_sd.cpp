#include "net/dns_sd.hpp"

#include <cstdio>

namespace rotord::net {

RotctldTxt::RotctldTxt(const ServicePorts& ports, const char* version) {
  add("txtvers", "1");
  add("version", version);
  const struct {
    const char* key;
    std::uint16_t port;
  } others[] = {{"web", ports.web},
                {"wrc", ports.wrc},
                {"gs232", ports.gs232},
                {"easycomm", ports.easycomm},
                {"seed", ports.seed}};
  for (const auto& other : others) {
    if (other.port == 0) continue;
    char port[8];
    std::snprintf(port, sizeof port, "%u", static_cast<unsigned>(other.port));
    add(other.key, port);
  }
}

void RotctldTxt::add(const char* key, const char* value) {
  if (count_ == kMaxRecords) return;
  // A version string longer than a record leaves it cut, never overflowing.
  std::snprintf(records_[count_], kMaxRecordBytes, "%s=%s", key, value);
  ++count_;
}

}  // namespace rotord::net
