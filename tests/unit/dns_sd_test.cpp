// The DNS-SD records every port announces (core/net/dns_sd.hpp): the Pico
// W's mDNS responder and Avahi on Linux publish these same TXT records.
#include "net/dns_sd.hpp"

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

TEST(DnsSd, TheRotctldRecordNamesTheVersionAndEveryOtherPortThatIsOn) {
  const RotctldTxt txt(ServicePorts{8080, 4533, 1234, 4601, 4602, 0}, "0.1.0");
  EXPECT_EQ(records(txt), (std::vector<std::string>{"txtvers=1", "version=0.1.0", "web=8080",
                                                    "wrc=1234", "gs232=4601", "easycomm=4602"}));
}

TEST(DnsSd, APortThatIsOffIsNotAnnounced) {
  const RotctldTxt txt(ServicePorts{80, 4533, 0, 0, 4602, 4700}, "1.2.3");
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
