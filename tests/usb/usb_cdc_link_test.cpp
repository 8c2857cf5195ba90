// The Pico W's USB CDC link (ports/pico_w/usb_cdc_link.cpp) on the host: the
// real sessions on a fake rotator, with a fake CDC interface in place of
// TinyUSB (the hardware boundary, fake_cdc.hpp).
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <string>

#include "fake_cdc.hpp"
#include "fake_rotator.hpp"
#include "protocol/console_session.hpp"
#include "settings/settings.hpp"
#include "string_sink.hpp"
#include "usb_cdc_link.hpp"
#include "usb_personality.hpp"

namespace rotord {
namespace {

using protocol::Personality;
using usb_port::PersonalitySessions;
using usb_port::UsbCdcLink;

using testing::FakeCdc;

class UsbCdcLinkTest : public ::testing::Test {
 protected:
  explicit UsbCdcLinkTest(Personality personality = Personality::kGs232)
      : sessions(personality, *rotator.controller, "test"), link(cdc, sessions) {
    cdc.plug();
    link.service();
  }

  /// The host writes, the firmware's loop passes once, the host reads.
  std::string ask(const std::string& bytes) {
    cdc.send(bytes);
    link.service();
    return cdc.take();
  }

  testing::FakeRotator rotator{false};
  FakeCdc cdc;
  PersonalitySessions sessions;
  UsbCdcLink link;
};

TEST_F(UsbCdcLinkTest, BytesReachTheSessionAndRepliesComeBackInOrder) {
  cdc.open();
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
  // Several commands in one USB packet and one split across two: replies in
  // the order of the commands.
  EXPECT_EQ(ask("C\rC2\rC"), "AZ=100\r\nAZ=100  EL=000\r\n");
  EXPECT_EQ(ask("\r"), "AZ=100\r\n");
  EXPECT_GT(cdc.flushes(), 0);  // short replies are pushed out, not held for a full packet
  EXPECT_EQ(link.stats().received_bytes, 9u);
}

TEST_F(UsbCdcLinkTest, CommandsMoveTheRotator) {
  cdc.open();
  EXPECT_EQ(ask("M200\r"), "\r");  // GS-232 acknowledges with a bare CR
  rotator.run_ms(20);
  EXPECT_TRUE(rotator.az.drive.cw());
  EXPECT_EQ(ask("S\r"), "\r");
  rotator.run_ms(20);
  EXPECT_FALSE(rotator.az.drive.cw());
}

TEST_F(UsbCdcLinkTest, GarbageGetsTheProtocolsErrorAndTheLineStaysUsable) {
  cdc.open();
  EXPECT_EQ(ask("Q\r"), "?>\r\n");
  EXPECT_EQ(ask(std::string("\x00\xff\x80zz\r", 6)), "?>\r\n");
  // A line far over GS-232's limit: one error, no crash, and the next
  // command works.
  const std::string reply = ask(std::string(4000, 'W') + "\r");
  EXPECT_EQ(reply.find("AZ="), std::string::npos);
  while (cdc.unread_input() > 0) link.service();
  cdc.take();
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
  EXPECT_FALSE(rotator.az.drive.cw() || rotator.az.drive.ccw());
}

TEST_F(UsbCdcLinkTest, ReopeningThePortStartsAFreshSession) {
  cdc.open();
  // The client dies in the middle of "M200\r": its half line must not join
  // the next client's first command.
  cdc.send("M2");
  link.service();
  cdc.close();
  link.service();
  cdc.open();
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");  // not "M2C" -> ?>
  rotator.run_ms(20);
  EXPECT_FALSE(rotator.az.drive.cw() || rotator.az.drive.ccw());
  EXPECT_EQ(link.stats().sessions, 4u);  // boot, open, close, reopen
}

TEST_F(UsbCdcLinkTest, CloseAndReopenBetweenTwoPassesIsStillSeen) {
  cdc.open();
  cdc.send("M2");
  link.service();
  cdc.close();
  cdc.open();  // a new program before the loop came round again
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
}

TEST_F(UsbCdcLinkTest, UnpluggingDropsUnreadInputAndOutput) {
  cdc.open();
  cdc.send("C\r");
  link.service();  // reply queued, never read
  cdc.send("M2");  // and half a command unread
  cdc.unplug();
  link.service();
  EXPECT_EQ(cdc.unread_input(), 0u);
  EXPECT_EQ(cdc.queued_output(), 0u);
  cdc.plug();
  cdc.open();
  link.service();
  EXPECT_EQ(ask("00\r"), "?>\r\n");  // "00" alone, not "M200"
  rotator.run_ms(20);
  EXPECT_FALSE(rotator.az.drive.cw());
}

TEST_F(UsbCdcLinkTest, ACommandSentJustBeforeTheCloseIsStillExecuted) {
  cdc.open();
  cdc.send("M200\r");
  cdc.close();  // printf 'M200\r' > /dev/ttyACM1
  link.service();
  rotator.run_ms(20);
  EXPECT_TRUE(rotator.az.drive.cw());
  EXPECT_EQ(cdc.queued_output(), 0u);  // its acknowledgement went nowhere
}

TEST_F(UsbCdcLinkTest, WithoutDtrOutputIsDroppedUntilTheClientSpeaks) {
  // The port is not open: unsolicited output must not pile up for the next
  // program.
  EXPECT_EQ(ask(""), "");
  // A program that never raises DTR (.NET SerialPort's default) but sends a
  // command is clearly listening: it gets its reply.
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
}

TEST_F(UsbCdcLinkTest, HostNotConnectedNeverBlocksAndDropsOutput) {
  cdc.unplug();
  link.service();
  link.poll(10);
  cdc.send("C\r");
  link.service();  // not configured: nothing is read
  EXPECT_EQ(cdc.unread_input(), 2u);
  EXPECT_EQ(cdc.queued_output(), 0u);
}

TEST_F(UsbCdcLinkTest, AFullTxFifoNeverBlocksAndDropsWholeRepliesCounted) {
  cdc.open();
  // The host stops reading: the FIFO (256 bytes) fills, then the link's
  // buffer (2048), then whole replies are dropped and counted.
  const std::size_t reply_bytes = std::string("AZ=100\r\n").size();
  const std::size_t capacity = FakeCdc::kFifoBytes + UsbCdcLink::kPendingBytes;
  const std::size_t asked = capacity / reply_bytes + 50;
  for (std::size_t i = 0; i < asked; ++i) {
    cdc.send("C\r");
    link.service();  // returns every time: the test would hang otherwise
  }
  const std::size_t kept = capacity / reply_bytes;
  EXPECT_EQ(link.stats().dropped_replies, asked - kept);
  EXPECT_EQ(link.stats().dropped_bytes, (asked - kept) * reply_bytes);
  EXPECT_EQ(link.pending_bytes(), kept * reply_bytes - FakeCdc::kFifoBytes);
  // The host reads again: every kept reply arrives whole, in order, and no
  // half reply is in the stream.
  std::string got;
  for (int pass = 0; pass < 20; ++pass) {
    got += cdc.take();
    link.service();
  }
  got += cdc.take();
  EXPECT_EQ(got.size(), kept * reply_bytes);
  for (std::size_t i = 0; i < got.size(); i += reply_bytes)
    ASSERT_EQ(got.substr(i, reply_bytes), "AZ=100\r\n") << "at byte " << i;
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
}

TEST_F(UsbCdcLinkTest, InputPerPassIsBoundedAndTheRestWaitsInTheFifo) {
  cdc.open();
  std::string many;
  for (int i = 0; i < 400; ++i) many += "S\r";  // 800 bytes, each acknowledged by a CR
  cdc.send(many);
  link.service();
  EXPECT_EQ(cdc.unread_input(), many.size() - UsbCdcLink::kMaxInputBytesPerService);
  std::string got = cdc.take();
  for (int pass = 0; pass < 10 && cdc.unread_input() > 0; ++pass) {
    link.service();
    got += cdc.take();
  }
  EXPECT_EQ(cdc.unread_input(), 0u);
  EXPECT_EQ(got, std::string(400, '\r'));
}

class UsbWrcTest : public UsbCdcLinkTest {
 protected:
  UsbWrcTest() : UsbCdcLinkTest(Personality::kWrc) {}
};

TEST_F(UsbWrcTest, MonitorOutputStopsWhenThePortCloses) {
  cdc.open();
  EXPECT_EQ(ask("MONITOR 1\r\n"), "OK MONITOR 1\r\n");
  link.poll(1000);
  link.service();
  const std::string pushed = cdc.take();
  EXPECT_EQ(pushed.find("OK STATE"), std::string::npos) << pushed;
  EXPECT_NE(pushed.find("STATE AZ=100.0"), std::string::npos) << pushed;
  cdc.close();
  link.service();
  link.poll(2000);
  link.service();
  EXPECT_EQ(cdc.queued_output(), 0u);
  // The next program gets a session with MONITOR off.
  cdc.open();
  link.service();
  link.poll(3000);
  link.service();
  EXPECT_EQ(cdc.take(), "");
}

/// Every personality answers garbage with its own protocol's error.
struct GarbageCase {
  Personality personality;
  const char* garbage;
  const char* error;
};

void PrintTo(const GarbageCase& c, std::ostream* os) {
  *os << usb_port::personality_name(c.personality);
}

class UsbPersonalityTest : public ::testing::TestWithParam<GarbageCase> {};

TEST_P(UsbPersonalityTest, GarbageGetsThisProtocolsError) {
  testing::FakeRotator rotator{false};
  FakeCdc cdc;
  PersonalitySessions sessions(GetParam().personality, *rotator.controller, "test");
  UsbCdcLink link(cdc, sessions);
  cdc.plug();
  cdc.open();
  link.service();
  cdc.send(GetParam().garbage);
  link.service();
  EXPECT_EQ(cdc.take(), GetParam().error);
  rotator.run_ms(20);
  EXPECT_FALSE(rotator.az.drive.cw() || rotator.az.drive.ccw());
}

INSTANTIATE_TEST_SUITE_P(
    All, UsbPersonalityTest,
    ::testing::Values(GarbageCase{Personality::kGs232, "Q\r", "?>\r\n"},
                      GarbageCase{Personality::kEasycomm, "FOO\n", "ALUNKNOWN\n"},
                      GarbageCase{Personality::kSeed, "$X\n", "$ERR,UNKNOWN\r\n"},
                      GarbageCase{Personality::kWrc, "FOO\r\n", "ERROR INVALID COMMAND\r\n"},
                      GarbageCase{Personality::kRotctld, "\\nosuchcommand\n", "RPRT -4\n"},
                      GarbageCase{Personality::kConsole, "FOO\r\n",
                                  "error: unknown command 'FOO' (help lists the commands)\r\n"}),
    [](const ::testing::TestParamInfo<GarbageCase>& param_info) {
      // "Yaesu GS-232" -> "Yaesu_GS_232": test names take letters, digits and '_'.
      std::string name = usb_port::personality_name(param_info.param.personality);
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

/// usb.personality = console: a listing longer than the link's 2 KB buffer
/// goes out whole, in pieces the buffer takes, while the host reads; what is
/// typed meanwhile waits in the FIFO and is answered after it.
TEST(UsbConsole, AListingLongerThanTheBufferComesOutWhole) {
  testing::FakeRotator rotator;
  settings::Settings defaults = rotator.settings;
  settings::Settings scratch;
  const protocol::ConsolePort port{&defaults, &scratch, nullptr, "test"};
  protocol::ConsoleSession reference(*rotator.controller, "test", &port);
  testing::StringSink expected;
  reference.receive("list\n", expected);
  protocol::drain_output(reference, expected);
  ASSERT_GT(expected.data.size(), UsbCdcLink::kPendingBytes + FakeCdc::kFifoBytes);

  FakeCdc cdc;
  PersonalitySessions sessions(Personality::kConsole, *rotator.controller, "test", &port);
  UsbCdcLink link(cdc, sessions);
  cdc.plug();
  cdc.open();
  link.service();
  cdc.send("list\r\n");
  link.service();
  cdc.send("get park.az_deg\r\n");
  link.service();
  EXPECT_GT(cdc.unread_input(), 0u);  // the get waits behind the listing
  std::string got;
  for (int pass = 0; pass < 200 && got.size() < expected.data.size() + 18; ++pass) {
    got += cdc.take();
    link.service();
  }
  got += cdc.take();
  EXPECT_EQ(got, expected.data + "ok park.az_deg=0\r\n");
  EXPECT_EQ(link.stats().dropped_replies, 0u);
}

// A protocol is offered on the Pico's USB by putting its key among the
// choices (docs/architecture.md); a row need not be offered, so the check runs
// from the choices to the rows: each is a row's key, once, and selects it.
TEST(UsbPersonality, TheSettingsChoicesAreOffAndRegistryKeysEachOnce) {
  const settings::Id id = settings::Id::kUsbPersonality;
  const settings::Def& def = settings::def(id);
  const int choices = settings::choice_count(id);
  ASSERT_GE(choices, 2);
  EXPECT_EQ(def.max, choices - 1);
  EXPECT_EQ(settings::choice_name(id, 0), "off");
  for (int n = 1; n < choices; ++n) {
    int rows_with_key = 0;
    for (const protocol::ProtocolInfo& p : protocol::protocols()) {
      if (settings::choice_name(id, n) != p.key) continue;
      ++rows_with_key;
      EXPECT_EQ(usb_port::personality_from_setting(n), p.personality) << p.key;
    }
    EXPECT_EQ(rows_with_key, 1) << settings::choice_name(id, n);
    for (int m = 1; m < n; ++m)
      EXPECT_NE(settings::choice_name(id, m), settings::choice_name(id, n));
  }
  EXPECT_EQ(usb_port::personality_from_setting(static_cast<int>(def.default_value)),
            Personality::kGs232);
  EXPECT_EQ(usb_port::personality_from_setting(0), std::nullopt);
  EXPECT_EQ(usb_port::personality_from_setting(-1), std::nullopt);
  EXPECT_EQ(usb_port::personality_from_setting(choices), std::nullopt);
  EXPECT_STREQ(usb_port::personality_name(Personality::kEasycomm), "Easycomm II/III");
  EXPECT_STREQ(usb_port::personality_name(std::nullopt), "off");
}

}  // namespace
}  // namespace rotord
