// The DNS-SD records every port announces (core/net/dns_sd.hpp): the Pico
// W's mDNS responder and Avahi on Linux publish these same TXT records.
#include "net/dns_sd.hpp"

#include "protocol/protocol_registry.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace rotord::net {
namespace {

std::vector<std::string> records(const RotctldTxt& txt) {
  std::vector<std::string> out;
  for (std::size_t n = 0; n < txt.size(); ++n) out.emplace_back(txt[n]);
  return out;
}

using protocol::Personality;

/// The ports as the registry's DNS-SD column announces them: `ports` in the
/// order of Personality (wrc, rotctld, gs232, easycomm, seed, console).
ServicePorts announced(std::uint16_t web, std::array<std::uint16_t, 6> ports) {
  return protocol::announced_ports(
      web, [&](Personality p) { return ports[static_cast<std::size_t>(p)]; });
}

TEST(DnsSd, TheRotctldRecordNamesTheVersionAndEveryOtherPortThatIsOn) {
  const ServicePorts ports = announced(8080, {1234, 4533, 4601, 4602, 0, 4604});
  EXPECT_EQ(ports.rotctld, 4533);  // the service itself, not in its TXT
  // The records as they were before the registry named them: the console
  // is not announced.
  const RotctldTxt txt(ports, "0.1.0");
  EXPECT_EQ(records(txt), (std::vector<std::string>{"txtvers=1", "version=0.1.0", "web=8080",
                                                    "wrc=1234", "gs232=4601", "easycomm=4602"}));
}

TEST(DnsSd, APortThatIsOffIsNotAnnounced) {
  const RotctldTxt txt(announced(80, {0, 4533, 0, 4602, 4700, 0}), "1.2.3");
  EXPECT_EQ(records(txt), (std::vector<std::string>{"txtvers=1", "version=1.2.3", "web=80",
                                                    "easycomm=4602", "seed=4700"}));
}

TEST(DnsSd, ALongVersionIsCutToTheRecordNotOverflowingIt) {
  const std::string long_version(100, 'v');
  const RotctldTxt txt(ServicePorts{}, long_version.c_str());
  ASSERT_EQ(txt.size(), 2u);
  EXPECT_EQ(std::strlen(txt[1]), RotctldTxt::kMaxRecordBytes - 1);
}

}  // namespace
}  // namespace rotord::net
