// The line protocols' command tables and their one reply type (issue 11):
// a reply that cannot fit becomes the protocol's error; each row's
// changes-state column is what a read-only client is refused; the GS-232
// help pages are generated from the rows, byte for byte as before.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "fake_rotator.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/line_reply.hpp"
#include "protocol/rotctld_reply.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;
using testing::StringSink;

constexpr ReplyRules kRules{"\r\n", "ERR OVERFLOW\r\n"};

TEST(LineReply, AReplyThatFitsGoesOutInOneWrite) {
  StringSink sink;
  LineReply<16> reply(kRules);
  reply.line(sink, "OK %d", 42);
  EXPECT_EQ(sink.data, "OK 42\r\n");
  EXPECT_EQ(sink.writes, 1);
}

TEST(LineReply, FillsItsCapacityExactly) {
  LineReply<8> reply(kRules);
  reply.format("%s", "123456");
  reply.end_line();
  EXPECT_FALSE(reply.overflowed());
  EXPECT_EQ(reply.view(), "123456\r\n");
}

TEST(LineReply, OneByteTooManyIsTheProtocolsErrorNotACutLine) {
  StringSink sink;
  LineReply<8> reply(kRules);
  reply.line(sink, "%s", "1234567");  // 7 + CR LF = 9
  EXPECT_EQ(sink.data, "ERR OVERFLOW\r\n");
  EXPECT_EQ(sink.writes, 1);

  LineReply<4> appended(kRules);
  appended.append("abc");
  appended.append("de");  // does not fit: the whole reply is the error
  appended.put('f');      // and stays so
  EXPECT_TRUE(appended.overflowed());
  EXPECT_EQ(appended.view(), "ERR OVERFLOW\r\n");
  appended.clear();
  appended.append("ok");
  EXPECT_EQ(appended.view(), "ok");
}

TEST(LineReply, AFixedTextIsNotAFormat) {
  LineReply<16> reply(kRules);
  reply.format("100%");
  EXPECT_EQ(reply.view(), "100%");
  StringSink sink;
  reply.text_line(sink, "%s%n");
  EXPECT_EQ(sink.data, "%s%n\r\n");
}

TEST(LineReply, EachProtocolOverflowsIntoItsOwnError) {
  EXPECT_EQ(WrcSession::kReplyRules.overflow, "ERROR REPLY TOO LONG\r\n");
  EXPECT_EQ(Gs232Session::kReplyRules.overflow, Gs232Session::kError);
  EXPECT_EQ(EasycommSession::kReplyRules.overflow, "ALOVERFLOW\n");
  EXPECT_EQ(SeedSession::kReplyRules.overflow, "$ERR,TOOLONG\r\n");
  EXPECT_EQ(rotctld::kReplyRules.overflow, "RPRT -10\n");  // RIG_ETRUNC
}

/// The help pages as the hand-written gs232_help.cpp (removed) had them before the
/// table (issue 11): generating them from the rows changed no byte.
TEST(Gs232Table, HelpPagesAreTheRowsByteForByteAsBefore) {
  EXPECT_EQ(Gs232Session::help_page(1),
            "---------- COMMAND LIST 1 ----------\r\n"
            "R      turn clockwise\r\n"
            "L      turn counter-clockwise\r\n"
            "A      stop azimuth\r\n"
            "C      report azimuth\r\n"
            "Maaa   turn to azimuth aaa\r\n"
            "Msss aaa aaa ...  timed list, sss seconds per step\r\n"
            "T      start the timed list\r\n"
            "N      timed list: point now and points stored\r\n"
            "X1-X4  azimuth speed, 1 slowest to 4 fastest\r\n"
            "S      stop everything\r\n"
            "O      offset calibration at the CCW stop\r\n"
            "F      full scale calibration at the CW stop\r\n");
  EXPECT_EQ(Gs232Session::help_page(2),
            "---------- COMMAND LIST 2 ----------\r\n"
            "U      turn up\r\n"
            "D      turn down\r\n"
            "E      stop elevation\r\n"
            "B      report elevation\r\n"
            "C2     report azimuth and elevation\r\n"
            "Waaa eee  turn to azimuth aaa, elevation eee\r\n"
            "Wsss aaa eee ...  timed list of pairs\r\n"
            "T      start the timed list\r\n"
            "N      timed list: point now and points stored\r\n"
            "S      stop everything\r\n"
            "O2     elevation offset calibration at the bottom\r\n"
            "F2     elevation full scale calibration at the top\r\n");
  EXPECT_EQ(Gs232Session::help_page(3),
            "---------- COMMAND LIST 3 ----------\r\n"
            "P36    360 degree azimuth scale\r\n"
            "P45    450 degree azimuth scale\r\n"
            "Z      toggle north / south centred needle\r\n");
  EXPECT_TRUE(Gs232Session::help_page(4).empty());
}

template <typename Table>
void expect_unique_names(const Table& table) {
  std::set<std::string> names;
  for (const auto& c : table) {
    EXPECT_TRUE(names.insert(std::string(c.name)).second) << c.name;
    EXPECT_FALSE(c.help.empty()) << c.name;
  }
}

TEST(CommandTables, NamesAreUniqueAndEveryRowHasHelp) {
  expect_unique_names(WrcSession::commands());
  expect_unique_names(Gs232Session::commands());
  expect_unique_names(EasycommSession::commands());
  expect_unique_names(SeedSession::commands());
}

/// Every row of every table, sent by a client outside
/// access.control_networks: refused in the protocol's way exactly when the
/// row says it changes state.
class ReadOnlyRows : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(r.settings.set_text(Id::kAccessControlNetworks, "10.0.0.0/8").error, Error::kOk);
    r.run_ms(50);
  }
  std::string ask(Session& session, const std::string& bytes) {
    session.set_peer(access::Peer::from_ipv4(0xC0A80114));  // 192.168.1.20
    StringSink sink;
    session.receive(bytes, sink);
    return sink.data;
  }
  testing::FakeRotator r;
};

TEST_F(ReadOnlyRows, Wrc) {
  for (const WrcSession::Command& c : WrcSession::commands()) {
    WrcSession s(*r.controller, "9");
    std::string line(c.name);
    if (c.arg == WrcSession::Arg::kRequired) line += " 1";
    const bool refused = ask(s, line + "\n") == "ERROR NOT ALLOWED\r\n";
    EXPECT_EQ(refused, c.changes_state) << line;
  }
}

TEST_F(ReadOnlyRows, Gs232) {
  for (const Gs232Session::Command& c : Gs232Session::commands()) {
    Gs232Session s(*r.controller);
    std::string line(1, c.letter);
    if (c.arg == Gs232Session::Arg::kExact) line += c.arg_text;
    if (c.arg == Gs232Session::Arg::kSpeed) line += "1";
    if (c.arg == Gs232Session::Arg::kList) line += c.letter == 'W' ? "100 010" : "100";
    const std::string reply = ask(s, line + "\r");
    // Refused rows answer ?> and change nothing; the others answer as they
    // do to a client that may control (?> is also GS-232's only error).
    if (c.changes_state) {
      EXPECT_EQ(reply, "?>\r\n") << line;
    } else {
      Gs232Session control(*r.controller);
      StringSink sink;
      control.receive(line + "\r", sink);
      EXPECT_EQ(reply, sink.data) << line;
    }
  }
  EXPECT_FALSE(r.controller->status().az.has_target);
}

TEST_F(ReadOnlyRows, Easycomm) {
  for (const EasycommSession::Command& c : EasycommSession::commands()) {
    EasycommSession s(*r.controller, "9");
    std::string token(c.name);
    using Arg = EasycommSession::Arg;
    if (c.arg == Arg::kQueryOrNumber) token += "10";
    if (c.arg == Arg::kVelocity) token += "0100";
    if (c.arg == Arg::kRegister) token += c.name == "CW" ? "park.az_deg,10" : "park.az_deg";
    if (c.arg == Arg::kFrequency || c.arg == Arg::kAny) token += "1";
    const std::string reply = ask(s, token + "\n");
    EXPECT_EQ(reply == "ALDENIED\n", c.changes_state) << token << " -> " << reply;
  }
}

TEST_F(ReadOnlyRows, Seed) {
  for (const SeedSession::Command& c : SeedSession::commands()) {
    SeedSession s(*r.controller);
    std::string line = "$" + std::string(c.name);
    for (int n = 0; n < c.args; ++n) line += ",cw";
    const bool refused = ask(s, line + "\n") == "$ERR,DENIED\r\n";
    EXPECT_EQ(refused, c.changes_state) << line;
  }
}

}  // namespace
}  // namespace rotord::protocol
