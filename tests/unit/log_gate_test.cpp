// The log's budget (core/access/log_gate.hpp), on plain data: one line a
// minute per source and the rest summed up, and a budget of lines a minute
// for the whole log that many sources taking turns cannot get past, their
// summaries included (issue 29).
#include "access/log_gate.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rotord::access {
namespace {

std::string text(const LogGate::Summary& s) {
  char buf[96];
  return LogGate::summary_text(s, buf, sizeof buf);
}

TEST(LogGate, OneLineASourceAMinuteThenItsSummary) {
  LogGate gate(10);
  LogGate::Summary evicted;
  const Peer a = Peer::from_ipv4(0xC0A80114);
  EXPECT_TRUE(gate.admit(a, 0, evicted));
  for (int n = 0; n < 99; ++n) EXPECT_FALSE(gate.admit(a, 10 + n, evicted));
  EXPECT_EQ(gate.next_due(59999).count, 0u);
  const LogGate::Summary s = gate.next_due(60000);
  EXPECT_EQ(s.count, 99u);
  EXPECT_EQ(text(s), "99 more from 192.168.1.20 in the last minute");
  EXPECT_EQ(gate.next_due(60000).count, 0u);
}

TEST(LogGate, ManySourcesTakingTurnsStayWithinTheBudget) {
  LogGate gate(10);
  int written = 0;
  for (int n = 0; n < 1000; ++n) {
    // 40 sources in turn, two lines each: each new one evicts a source with
    // a line to sum up.
    LogGate::Summary evicted;
    const auto source = static_cast<unsigned>(n / 2 % 40);
    const bool line = gate.admit(Peer::from_ipv4(0x0A000000u + source), n, evicted);
    written += line ? 1 : 0;
    written += evicted.count > 0 ? 1 : 0;
  }
  EXPECT_LE(written, 10);
  // The minute's end: a summary per source followed, and one of the rest.
  int summaries = 0;
  std::uint32_t over_budget = 0;
  for (LogGate::Summary s = gate.next_due(60000); s.count > 0; s = gate.next_due(60000)) {
    ++summaries;
    if (s.source.kind == Peer::Kind::kUnknown) over_budget = s.count;
  }
  EXPECT_LE(summaries, static_cast<int>(LogGate::kSources) + 1);
  EXPECT_GT(over_budget, 900u);
}

TEST(LogGate, TheSummaryOfAnIpv6HostNamesIts64) {
  IpBytes a{};
  a[0] = 0x20;
  a[1] = 0x01;
  a[2] = 0x0D;
  a[3] = 0xB8;
  a[7] = 0x02;
  a[15] = 0x99;
  EXPECT_EQ(text({Peer::from_ipv6(a), 5}), "5 more from 2001:db8:0:2::/64 in the last minute");
  EXPECT_EQ(text({Peer{}, 7}), "7 more log lines in the last minute, over the log's budget");
}

}  // namespace
}  // namespace rotord::access
