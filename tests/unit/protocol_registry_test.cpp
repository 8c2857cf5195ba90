// The one protocol registry (issue 11) both ports serve from: one row per
// personality, each building its own session, with distinct keys and ports.
#include "protocol/protocol_registry.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <new>
#include <set>
#include <string>

#include "fake_rotator.hpp"
#include "metrics/registry.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

TEST(ProtocolRegistry, OneRowPerPersonalityWithDistinctKeysAndPorts) {
  ASSERT_EQ(protocols().size(), kPersonalityCount);
  std::set<std::string_view> keys;
  std::set<int> ports;
  for (std::size_t n = 0; n < protocols().size(); ++n) {
    const ProtocolInfo& p = protocols()[n];
    EXPECT_EQ(static_cast<std::size_t>(p.personality), n) << p.key;
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_TRUE(ports.insert(p.tcp_port).second) << p.key;
    EXPECT_NE(p.tcp_port, 0) << p.key;  // the Pico W serves every row on TCP
    EXPECT_EQ(&protocol_info(p.personality), &p);
    EXPECT_EQ(find_protocol(p.key), &p);
    // The /metrics label is the key, so a port counts each under its name.
    EXPECT_EQ(metrics::protocol_label(p.metric()), p.key);
    EXPECT_FALSE(p.name.empty());
    EXPECT_GE(p.serial_baud, 1200);
  }
  EXPECT_EQ(find_protocol("nosuch"), nullptr);
  EXPECT_EQ(find_protocol("GS232"), nullptr);  // keys are exact
  // The defaults the ports had before the registry.
  EXPECT_EQ(protocol_info(Personality::kWrc).tcp_port, 1234);
  EXPECT_EQ(protocol_info(Personality::kRotctld).tcp_port, 4533);
  EXPECT_EQ(protocol_info(Personality::kGs232).tcp_port, 4601);
  EXPECT_EQ(protocol_info(Personality::kEasycomm).tcp_port, 4602);
  EXPECT_EQ(protocol_info(Personality::kSeed).tcp_port, 4603);
  EXPECT_FALSE(protocol_info(Personality::kSeed).tcp_by_default);  // Linux: --seed-port
  // The Pico W's TCP pools as network_services.cpp listed them before the
  // rows sized them: the console on USB only there.
  int pico_slots = 0;
  for (const ProtocolInfo& p : protocols()) pico_slots += p.pico_tcp_slots;
  EXPECT_EQ(pico_slots, 4 + 3 + 2 + 2 + 2);
  EXPECT_EQ(protocol_info(Personality::kWrc).pico_tcp_slots, 4);
  EXPECT_EQ(protocol_info(Personality::kRotctld).pico_tcp_slots, 3);
  EXPECT_EQ(protocol_info(Personality::kConsole).pico_tcp_slots, 0);
}

/// Each row's session factory builds that protocol: garbage gets its error,
/// and a refused connection its own refusal.
// usb.personality's choices are checked against the rows at compile time
// (protocol_registry.cpp); the check refuses each way they could drift.
TEST(ProtocolRegistry, TheUsbChoicesCheckRefusesADriftedList) {
  EXPECT_TRUE(offers_off_and_rows("off|gs232|easycomm|seed|wrc|rotctld|console"));
  EXPECT_TRUE(offers_off_and_rows("off|wrc|rotctld|gs232|easycomm|seed|console"));
  // A row need not be offered on USB.
  EXPECT_TRUE(offers_off_and_rows("off|gs232|easycomm|seed|wrc|rotctld"));
  // A choice that is no row's key (a typo, a key renamed), one twice, no
  // "off" first, nothing at all.
  EXPECT_FALSE(offers_off_and_rows("off|gs232|easycomm|seed|wrc|rotctl|console"));
  EXPECT_FALSE(offers_off_and_rows("off|gs232|easycomm|seed|wrc|rotctld|console|wrc"));
  EXPECT_FALSE(offers_off_and_rows("gs232|off|easycomm|seed|wrc|rotctld|console"));
  EXPECT_FALSE(offers_off_and_rows(""));
}

TEST(ProtocolRegistry, EachRowBuildsItsOwnSession) {
  struct Case {
    Personality personality;
    const char* garbage;
    const char* error;
    std::string_view refusal;
  };
  const Case cases[] = {
      {Personality::kWrc, "FOO\r\n", "ERROR INVALID COMMAND\r\n", "ERROR TOO MANY CONNECTIONS\r\n"},
      {Personality::kRotctld, "\\nosuchcommand\n", "RPRT -4\n", "RPRT -9\n"},
      {Personality::kGs232, "Q\r", "?>\r\n", "?>\r\n"},
      {Personality::kEasycomm, "FOO\n", "ALUNKNOWN\n", "ALBUSY\n"},
      {Personality::kSeed, "$X\n", "$ERR,UNKNOWN\r\n", "$ERR,BUSY\r\n"},
  };
  testing::FakeRotator r;
  const SessionDeps deps{*r.controller, "9"};
  for (const Case& c : cases) {
    EXPECT_EQ(protocol_info(c.personality).refusal, c.refusal);
    alignas(kAnySessionAlign) unsigned char storage[kAnySessionBytes];
    Session* s = with_session_type(c.personality, [&](auto session) -> Session* {
      using S = typename decltype(session)::type;
      static_assert(sizeof(S) <= kAnySessionBytes && alignof(S) <= kAnySessionAlign);
      return ::new (static_cast<void*>(storage)) S(decltype(session)::make(deps));
    });
    testing::StringSink sink;
    s->receive(c.garbage, sink);
    EXPECT_EQ(sink.data, c.error) << protocol_info(c.personality).key;
    // The row's own error recognition (the /metrics error count) knows it,
    // and the busy refusal too; not a reply that is no error.
    const ProtocolInfo& row = protocol_info(c.personality);
    EXPECT_TRUE(row.is_error_reply(c.error)) << row.key;
    EXPECT_TRUE(row.is_error_reply(c.refusal)) << row.key;
    EXPECT_FALSE(row.is_error_reply("\r\n")) << row.key;
    EXPECT_EQ(find_protocol(row.metric()), &row);
    s->~Session();
  }
}

}  // namespace
}  // namespace rotord::protocol
