// The Linux port's log lines (log.hpp): the text form rotord always printed,
// and the JSON form's time, level and escaping.
#include "log.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <string>

namespace rotord::linux_port::log {
namespace {

TEST(LogLine, TextIsTheMessageAfterTheProgramName) {
  EXPECT_EQ(format_line(Format::kText, Level::kWarn, "gpiod: reading x failed", 0),
            "rotord: gpiod: reading x failed");
}

TEST(LogLine, JsonHasUtcMillisecondTimeLevelAndMessage) {
  // 2026-11-24T10:15:00.123Z
  EXPECT_EQ(format_line(Format::kJson, Level::kInfo, "ready", 1795515300123),
            "{\"time\":\"2026-11-24T10:15:00.123Z\",\"level\":\"info\",\"msg\":\"ready\"}");
  EXPECT_EQ(format_line(Format::kJson, Level::kDebug, "x", 0),
            "{\"time\":\"1970-01-01T00:00:00.000Z\",\"level\":\"debug\",\"msg\":\"x\"}");
}

TEST(LogLine, JsonEscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(format_line(Format::kJson, Level::kError, "a \"b\" c\\d\ne\tf\x01 \xc2\xb0", 0),
            "{\"time\":\"1970-01-01T00:00:00.000Z\",\"level\":\"error\",\"msg\":"
            "\"a \\\"b\\\" c\\\\d\\ne\\tf\\u0001 \xc2\xb0\"}");
}

TEST(LogLine, UnderTheJournalEveryLineStartsWithItsSyslogPriority) {
  EXPECT_EQ(format_line(Format::kText, Level::kError, "cannot listen", 0, true),
            "<3>cannot listen");
  EXPECT_EQ(format_line(Format::kText, Level::kWarn, "w", 0, true), "<4>w");
  EXPECT_EQ(format_line(Format::kText, Level::kInfo, "ready", 0, true), "<6>ready");
  EXPECT_EQ(format_line(Format::kText, Level::kDebug, "d", 0, true), "<7>d");
  EXPECT_EQ(format_line(Format::kJson, Level::kWarn, "x", 0, true),
            "<4>{\"time\":\"1970-01-01T00:00:00.000Z\",\"level\":\"warn\",\"msg\":\"x\"}");
}

TEST(LogJournal, OnlyTheStreamJournalStreamNamesCounts) {
  struct stat st {};
  ASSERT_EQ(::fstat(2, &st), 0);
  const std::string mine = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  ::unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(stdio_is_journal());
  ::setenv("JOURNAL_STREAM", mine.c_str(), 1);
  EXPECT_TRUE(stdio_is_journal());
  // Inherited from a parent whose stream was another one: not the journal.
  ::setenv("JOURNAL_STREAM", (std::to_string(st.st_dev) + ":1").c_str(), 1);
  EXPECT_FALSE(stdio_is_journal());
  ::setenv("JOURNAL_STREAM", "garbage", 1);
  EXPECT_FALSE(stdio_is_journal());
  ::unsetenv("JOURNAL_STREAM");
}

TEST(LogLevel, NamesParseAndFilter) {
  Level level = Level::kInfo;
  EXPECT_TRUE(parse_level("debug", level));
  EXPECT_EQ(level, Level::kDebug);
  EXPECT_TRUE(parse_level("warning", level));
  EXPECT_EQ(level, Level::kWarn);
  EXPECT_FALSE(parse_level("verbose", level));
  EXPECT_EQ(level, Level::kWarn);  // unchanged
  configure(Level::kWarn, Format::kText);
  EXPECT_TRUE(enabled(Level::kError));
  EXPECT_TRUE(enabled(Level::kWarn));
  EXPECT_FALSE(enabled(Level::kInfo));
  configure(Level::kInfo, Format::kText);
}

}  // namespace
}  // namespace rotord::linux_port::log
