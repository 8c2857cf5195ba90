// The Pico W's USB log port (ports/pico_w/log_port.cpp) on the host, against
// the fake CDC interface: what printf wrote before a terminal opened the
// port reaches the terminal when it does, in order, and nothing waits for
// the host.
#include "log_port.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_cdc.hpp"
#include "fake_rotator.hpp"
#include "protocol/console_session.hpp"
#include "string_sink.hpp"

namespace rotord {
namespace {

using testing::FakeCdc;
using usb_port::LogPort;

class LogPortTest : public ::testing::Test {
 protected:
  LogPortTest() { cdc.plug(); }

  /// The terminal reads while the firmware's loop passes, until nothing is
  /// left: the FIFO holds 256 bytes, so a long backlog takes several passes.
  std::string read_all() {
    std::string got;
    for (int pass = 0; pass < 100; ++pass) {
      log.service();
      const std::string chunk = cdc.take();
      if (chunk.empty() && log.backlog_bytes() == 0) break;
      got += chunk;
    }
    return got;
  }

  /// `count` numbered log lines, as printf writes them (CRLF).
  static std::string lines(int first, int count) {
    std::string text;
    for (int i = first; i < first + count; ++i)
      text += "rotord: line " + std::to_string(i) + " of the boot log\r\n";
    return text;
  }

  FakeCdc cdc;
  LogPort log{cdc};
};

TEST_F(LogPortTest, LinesWrittenBeforeATerminalOpensThePortAreReplayedWhenItDoes) {
  const std::string boot = lines(1, 40);  // about 1.3 KB, five FIFOs' worth
  log.write(boot);
  log.service();  // loop passes with nobody listening send nothing
  log.service();
  EXPECT_EQ(cdc.queued_output(), 0u);
  EXPECT_EQ(log.backlog_bytes(), boot.size());

  cdc.open();
  log.write("rotord: after the open\r\n");  // behind the backlog, not ahead of it
  EXPECT_EQ(read_all(), boot + "rotord: after the open\r\n");
  EXPECT_EQ(log.stats().dropped_bytes, 0u);
  EXPECT_GT(cdc.flushes(), 0);  // pushed out, not held for a full packet
}

TEST_F(LogPortTest, WithATerminalListeningOutputGoesStraightOut) {
  cdc.open();
  log.write("rotord: Wi-Fi joined\r\n");
  EXPECT_EQ(cdc.take(), "rotord: Wi-Fi joined\r\n");  // no loop pass needed
  EXPECT_EQ(log.backlog_bytes(), 0u);
}

TEST_F(LogPortTest, WhatTheTerminalReadIsNotReplayedToTheNext) {
  cdc.open();
  log.write("seen by the first\r\n");
  EXPECT_EQ(read_all(), "seen by the first\r\n");
  cdc.close();
  log.write("while closed\r\n");
  cdc.open();
  EXPECT_EQ(read_all(), "while closed\r\n");
}

TEST_F(LogPortTest, ClosingMidReplayKeepsTheRestForTheNextTerminal) {
  const std::string boot = lines(1, 40);
  log.write(boot);
  cdc.open();
  log.service();
  std::string got = cdc.take();  // one FIFO's worth
  EXPECT_EQ(got.size(), FakeCdc::kFifoBytes);
  cdc.close();
  log.service();
  EXPECT_EQ(cdc.queued_output(), 0u);
  cdc.open();
  got += read_all();
  EXPECT_EQ(got, boot);
}

TEST_F(LogPortTest, AFullRingKeepsTheNewestWholeLinesAndSaysHowMuchWasDropped) {
  const std::string old_lines = lines(1, 100);
  const std::string new_lines = lines(1000, 100);
  ASSERT_GT(old_lines.size() + new_lines.size(), LogPort::kRingBytes);
  ASSERT_LT(new_lines.size(), LogPort::kRingBytes);
  log.write(old_lines);
  log.write(new_lines);
  EXPECT_LE(log.backlog_bytes(), LogPort::kRingBytes);
  const std::uint32_t dropped = log.stats().dropped_bytes;
  EXPECT_EQ(dropped + log.backlog_bytes(), old_lines.size() + new_lines.size());

  cdc.open();
  const std::string got = read_all();
  const std::string note = "rotord: log: " + std::to_string(dropped) +
                           " bytes of older lines dropped (the log port was not read)\r\n";
  ASSERT_EQ(got.substr(0, note.size()), note);
  const std::string kept = got.substr(note.size());
  // The newest lines, whole: what was kept is the end of what was written,
  // starting on a line.
  EXPECT_EQ(kept, (old_lines + new_lines).substr(dropped));
  EXPECT_EQ(kept.rfind(new_lines), kept.size() - new_lines.size());
  EXPECT_EQ(kept.substr(0, 13), "rotord: line ");
}

TEST_F(LogPortTest, AWriteLargerThanTheRingKeepsItsEnd) {
  std::string huge(LogPort::kRingBytes + 100, 'x');
  huge.back() = '\n';
  log.write("first\r\n");
  log.write(huge);
  EXPECT_EQ(log.backlog_bytes(), LogPort::kRingBytes);
  EXPECT_EQ(log.stats().dropped_bytes, 7u + 100u);
}

TEST_F(LogPortTest, ATerminalThatStopsReadingNeverStallsTheWriter) {
  cdc.open();
  // Nobody takes from the FIFO: it fills, then the ring, then the oldest go.
  for (int i = 0; i < 500; ++i) {
    log.write(lines(i, 1));
    log.service();
  }
  EXPECT_EQ(cdc.queued_output(), FakeCdc::kFifoBytes);
  EXPECT_GT(log.stats().dropped_bytes, 0u);
  // It reads again: the newest lines arrive, after a note of the gap.
  cdc.take();
  const std::string got = read_all();
  EXPECT_NE(got.find("bytes of older lines dropped"), std::string::npos);
  EXPECT_EQ(got.substr(got.size() - lines(499, 1).size()), lines(499, 1));
}

TEST_F(LogPortTest, LiveOnlyOutputIsDroppedWhileNobodyListens) {
  log.write("rotord: boot\r\n");
  log.write_live("AZ=100 EL=000\r\n");  // a WRC MONITOR line: no use later
  EXPECT_EQ(log.stats().unheard_bytes, 15u);
  cdc.open();
  EXPECT_EQ(read_all(), "rotord: boot\r\n");
  log.write_live("AZ=101 EL=000\r\n");
  EXPECT_EQ(read_all(), "AZ=101 EL=000\r\n");
}

TEST_F(LogPortTest, NothingGoesOutBeforeTheHostConfiguresTheDevice) {
  cdc.unplug();
  log.write("rotord: before enumeration\r\n");
  log.service();
  EXPECT_EQ(cdc.queued_output(), 0u);
  cdc.plug();
  cdc.open();
  EXPECT_EQ(read_all(), "rotord: before enumeration\r\n");
}

TEST_F(LogPortTest, InputOnTheLogPortIsDropped) {
  cdc.open();
  cdc.send("typed into the log terminal\r");
  log.service();
  EXPECT_EQ(cdc.unread_input(), 0u);  // no FIFO left full, no NAKs
}

/// The console (protocol/console_session.hpp) on the log port, as the
/// firmware serves it (main.cpp): commands typed into the log terminal, the
/// replies in the log's order.
class LogPortConsoleTest : public LogPortTest {
 protected:
  LogPortConsoleTest() {
    rotator.run_ms(50);
    log.attach_console(console);
  }
  testing::FakeRotator rotator;
  settings::Settings defaults = rotator.settings;
  settings::Settings scratch;
  protocol::ConsolePort port{&defaults, &scratch, nullptr, "test"};
  protocol::ConsoleSession console{*rotator.controller, "9.9.9", &port};
};

TEST_F(LogPortConsoleTest, ACommandTypedIntoTheLogTerminalIsAnsweredInTheLog) {
  log.write("rotord: boot line\r\n");
  cdc.open();
  cdc.send("get az.max_deg\r");
  EXPECT_EQ(read_all(), "rotord: boot line\r\nok az.max_deg=450\r\n");
  cdc.send("set az.max_deg 400\r\nfrobnicate\r\n");
  EXPECT_EQ(read_all(),
            "ok az.max_deg=400\r\nerror: unknown command 'frobnicate' (help lists the "
            "commands)\r\n");
  EXPECT_EQ(rotator.settings.get(settings::Id::kAzMaxDeg), 400);
}

TEST_F(LogPortConsoleTest, AListingLongerThanTheRingComesOutWholeAndInputWaitsForIt) {
  // What the listing is, from the same session type on an unbounded sink.
  protocol::ConsoleSession reference(*rotator.controller, "9.9.9", &port);
  testing::StringSink expected;
  reference.receive("list\n", expected);
  protocol::drain_output(reference, expected);
  ASSERT_GT(expected.data.size(), LogPort::kRingBytes);  // several windows

  const std::string boot = lines(1, 60);  // about 2 KB of the ring already taken
  log.write(boot);
  cdc.open();
  cdc.send("list\r");
  log.service();
  ASSERT_TRUE(console.output_pending());
  cdc.send("get park.az_deg\r");  // typed during the listing: waits in the FIFO
  log.service();                  // the terminal reads nothing yet: no room, nothing more goes out
  log.service();
  EXPECT_TRUE(console.output_pending());
  EXPECT_GT(cdc.unread_input(), 0u);
  EXPECT_EQ(read_all(), boot + expected.data + "ok park.az_deg=0\r\n");
  EXPECT_EQ(log.stats().dropped_bytes, 0u);
}

TEST_F(LogPortConsoleTest, AReadOnlyLogTerminalMayReadButNotChange) {
  rotator.settings.set(settings::Id::kAccessLineControl, 0);
  cdc.open();
  cdc.send("set az.max_deg 400\rget az.max_deg\r");
  const std::string reply = read_all();
  EXPECT_EQ(reply.rfind("error: read-only", 0), 0u) << reply;
  EXPECT_NE(reply.find("\r\nok az.max_deg=450\r\n"), std::string::npos) << reply;
}

}  // namespace
}  // namespace rotord
