#include "net/dns_sd.hpp"

#include <cstdio>

namespace rotord::net {

RotctldTxt::RotctldTxt(const ServicePorts& ports, const char* version) {
  add("txtvers", "1");
  add("version", version);
  add_port("web", ports.web);
  for (std::size_t n = 0; n < ports.other_count; ++n)
    add_port(ports.others[n].key, ports.others[n].port);
}

void RotctldTxt::add_port(const char* key, std::uint16_t port) {
  if (port == 0) return;
  char text[8];
  std::snprintf(text, sizeof text, "%u", static_cast<unsigned>(port));
  add(key, text);
}

void RotctldTxt::add(const char* key, const char* value) {
  if (count_ == kMaxRecords) return;
  // A version string longer than a record leaves it cut, never overflowing.
  std::snprintf(records_[count_], kMaxRecordBytes, "%s=%s", key, value);
  ++count_;
}

}  // namespace rotord::net
