#pragma once
// rotord's log on Linux: --log-level error|warn|info|debug, --log-format
// text|json. Text lines are "rotord: <message>" as they always were (info
// and debug on standard output, warnings and errors on standard error, so
// journald and a terminal tell them apart); JSON is one object per line on
// the same streams:
//   {"time":"2026-11-24T10:15:00.123Z","level":"info","msg":"ready"}
// Under systemd (JOURNAL_STREAM names standard output or error, see
// systemd.exec(5)) every line starts with its syslog priority, "<3>" error,
// "<4>" warning, "<6>" info, "<7>" debug, which journald turns into the
// entry's priority (`journalctl -p warning -u rotord`), and text lines drop
// the "rotord: " the journal already shows as rotord[pid].
// One process-wide setting, made once by main() before anything logs.
//
// Nobody floods it (issue 29, docs/security.md "Logs"): every line at info,
// warn and error goes through one budget of kLinesPerMinute lines a minute
// for the whole process (access/log_gate.hpp), the web's access log
// included; a refusal or error caused by a client (from()) is written once a
// minute per source, the rest summed up as "N more from ADDR in the last
// minute". Debug lines are outside the budget: --log-level debug traces
// every connection and datagram on purpose, for diagnosis, not service.
#include <cstdint>
#include <string>
#include <string_view>

#include "access/log_gate.hpp"

namespace rotord::linux_port::log {

enum class Level : std::uint8_t { kError, kWarn, kInfo, kDebug };
enum class Format : std::uint8_t { kText, kJson };

/// "error", "warn", "info", "debug" (and "warning"); false for anything else.
bool parse_level(std::string_view text, Level& level);
const char* level_name(Level level);

/// `journal`: lines carry the syslog priority prefix (see above).
void configure(Level level, Format format, bool journal = false);
/// Whether standard output or error is connected to the journal: the
/// device and inode in $JOURNAL_STREAM are those of fd 1 or 2.
bool stdio_is_journal();
/// The syslog priority journald reads from the "<N>" prefix.
int syslog_priority(Level level);
/// Whether a message at `level` is written (skip building costly ones).
bool enabled(Level level);

/// One line as it goes out, without the line end: the text form or the
/// JSON object, `unix_ms` its time; `journal` adds the priority prefix.
/// Exposed for tests.
std::string format_line(Format format, Level level, std::string_view message, std::int64_t unix_ms,
                        bool journal = false);

/// Lines a minute at info, warn and error, for the whole process: room for
/// the start-up's ~30 and a busy minute's own lines.
inline constexpr unsigned kLinesPerMinute = 120;

/// The process's budget, shared with the web's access log (web::Context::log_gate).
access::LogGate& gate();
/// The network's clock (the manual clock under --clock manual): the budget's
/// minutes, and the summaries that are due are written now. Call every pass.
void tick(Millis now_ms);

/// A refusal or error caused by `source` (printf-style): the first from its
/// host in a minute is written, the rest summed up when that minute ends.
void from(const access::Peer& source, Level level, const char* fmt, ...)
    __attribute__((format(printf, 3, 4)));

/// printf-style; the message has no "rotord: " prefix and no line end.
void error(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
void warn(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
void info(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
void debug(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
/// An answer on standard output whatever --log-level says, written as an
/// info line: the manual clock's replies, which a test waits for.
void reply(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace rotord::linux_port::log
