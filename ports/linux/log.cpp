#include "log.hpp"

#include <sys/stat.h>

#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace rotord::linux_port::log {
namespace {

Level g_level = Level::kInfo;
Format g_format = Format::kText;
bool g_journal = false;
access::LogGate g_gate(kLinesPerMinute);
Millis g_now_ms = 0;

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", u);
      out += esc;
    } else {
      out += c;  // UTF-8 passes through as it is
    }
  }
  out += '"';
}

std::int64_t unix_ms_now() {
  using namespace std::chrono;
  return duration_cast<milliseconds>(system_clock::now().time_since_epoch()).count();
}

/// `budget`: the line counts against the process's budget (and is dropped
/// over it); replies and summaries do not.
void vwrite(Level level, const char* fmt, va_list args, bool always = false, bool budget = true) {
  if (!always && !enabled(level)) return;
  if (budget && !always && level != Level::kDebug && !g_gate.admit_line(g_now_ms)) return;
  char stack[512];
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(stack, sizeof stack, fmt, copy);
  va_end(copy);
  std::string message;
  if (n < 0) {
    message = fmt;
  } else if (static_cast<std::size_t>(n) < sizeof stack) {
    message.assign(stack, static_cast<std::size_t>(n));
  } else {
    message.resize(static_cast<std::size_t>(n) + 1);
    std::vsnprintf(message.data(), message.size(), fmt, args);
    message.resize(static_cast<std::size_t>(n));
  }
  const std::string line = format_line(g_format, level, message, unix_ms_now(), g_journal) + "\n";
  std::FILE* stream = level <= Level::kWarn ? stderr : stdout;
  // A closed terminal or pipe (SIGPIPE is ignored) makes this fail: nothing
  // else to do with a log line nobody can read.
  std::fwrite(line.data(), 1, line.size(), stream);
  std::fflush(stream);
}

}  // namespace

bool parse_level(std::string_view text, Level& level) {
  if (text == "error") {
    level = Level::kError;
  } else if (text == "warn" || text == "warning") {
    level = Level::kWarn;
  } else if (text == "info") {
    level = Level::kInfo;
  } else if (text == "debug") {
    level = Level::kDebug;
  } else {
    return false;
  }
  return true;
}

const char* level_name(Level level) {
  switch (level) {
    case Level::kError:
      return "error";
    case Level::kWarn:
      return "warn";
    case Level::kInfo:
      return "info";
    case Level::kDebug:
      return "debug";
  }
  return "?";
}

void configure(Level level, Format format, bool journal) {
  g_level = level;
  g_format = format;
  g_journal = journal;
}

bool stdio_is_journal() {
  const char* stream = std::getenv("JOURNAL_STREAM");
  if (stream == nullptr) return false;
  unsigned long long dev = 0;
  unsigned long long ino = 0;
  if (std::sscanf(stream, "%llu:%llu", &dev, &ino) != 2) return false;
  // Inherited by a child whose output goes elsewhere (a pipe, a file), the
  // variable alone would be wrong: only the very stream journald gave counts.
  for (const int fd : {1, 2}) {
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_dev == dev && st.st_ino == ino) return true;
  }
  return false;
}

int syslog_priority(Level level) {
  switch (level) {
    case Level::kError:
      return 3;  // LOG_ERR
    case Level::kWarn:
      return 4;  // LOG_WARNING
    case Level::kInfo:
      return 6;  // LOG_INFO
    case Level::kDebug:
      return 7;  // LOG_DEBUG
  }
  return 6;
}

bool enabled(Level level) {
  return level <= g_level;
}

std::string format_line(Format format, Level level, std::string_view message, std::int64_t unix_ms,
                        bool journal) {
  std::string line;
  if (journal) {
    line = "<" + std::to_string(syslog_priority(level)) + ">";
    if (format == Format::kText) return line.append(message);
  }
  if (format == Format::kText) return "rotord: " + std::string(message);
  const std::time_t seconds = static_cast<std::time_t>(unix_ms / 1000);
  std::tm utc{};
  ::gmtime_r(&seconds, &utc);
  char time[80];
  std::snprintf(time, sizeof time, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                static_cast<int>(unix_ms % 1000));
  line += "{\"time\":\"";
  line += time;
  line += "\",\"level\":\"";
  line += level_name(level);
  line += "\",\"msg\":";
  append_json_string(line, message);
  line += '}';
  return line;
}

/// A line outside the budget (a summary: at most one per source a minute).
static void write_unbudgeted(Level level, const char* fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void write_unbudgeted(Level level, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(level, fmt, args, false, false);
  va_end(args);
}

static void write_summary(const access::LogGate::Summary& s) {
  char text[96];
  write_unbudgeted(Level::kWarn, "%s", access::LogGate::summary_text(s, text, sizeof text));
}

access::LogGate& gate() {
  return g_gate;
}

void tick(Millis now_ms) {
  g_now_ms = now_ms;
  for (access::LogGate::Summary s = g_gate.next_due(now_ms); s.count > 0;
       s = g_gate.next_due(now_ms))
    write_summary(s);
}

void from(const access::Peer& source, Level level, const char* fmt, ...) {
  if (!enabled(level)) return;
  access::LogGate::Summary evicted;
  const bool write = g_gate.admit(source, g_now_ms, evicted);
  if (evicted.count > 0) write_summary(evicted);
  if (!write) return;
  va_list args;
  va_start(args, fmt);
  vwrite(level, fmt, args, false, false);  // admit() counted it
  va_end(args);
}

void error(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(Level::kError, fmt, args);
  va_end(args);
}

void warn(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(Level::kWarn, fmt, args);
  va_end(args);
}

void info(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(Level::kInfo, fmt, args);
  va_end(args);
}

void debug(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(Level::kDebug, fmt, args);
  va_end(args);
}

void reply(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  vwrite(Level::kInfo, fmt, args, true);
  va_end(args);
}

}  // namespace rotord::linux_port::log
