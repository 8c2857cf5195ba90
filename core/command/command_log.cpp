#include "command/command_log.hpp"

#include <cstdarg>
#include <cstdio>

namespace rotord::command {

Error told(Controller& controller, const Origin& from, std::string_view what, Error outcome,
           float az_deg, float el_deg, std::string_view args) {
  told(controller, from, what, error_name(outcome), az_deg, el_deg, args);
  return outcome;
}

void told(Controller& controller, const Origin& from, std::string_view what,
          std::string_view outcome, float az_deg, float el_deg, std::string_view args) {
  if (CommandJournal* j = controller.journal(); j != nullptr && !from.front.empty())
    j->record({what, args, from.front, from.peer, az_deg, el_deg, outcome});
}

namespace {

/// " (192.168.1.20)" after the front end, or nothing without a client.
const char* client_text(const access::Peer& peer, char (&text)[access::kAddressTextBytes + 3]) {
  text[0] = '\0';
  if (peer.kind == access::Peer::Kind::kUnknown) return text;
  char address[access::kAddressTextBytes];
  std::snprintf(text, sizeof text, " (%s)", access::peer_text(peer, address));
  return text;
}

/// Tells a command's words apart (FNV-1a), without keeping them: they may
/// live in the caller's buffer.
std::uint32_t hash(std::string_view words) {
  std::uint32_t h = 2166136261u;
  for (const char c : words) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h;
}

}  // namespace

void CommandLog::record(const CommandEntry& e) {
  const std::uint32_t args = hash(e.args);
  Repeat* slot = &repeats_[0];  // a free one, else the oldest
  for (Repeat& r : repeats_) {
    if (r.used && r.what == e.what && r.args == args && r.front == e.front &&
        r.outcome == e.outcome && r.peer.same_host(e.peer)) {
      ++r.count;  // its line is written; the minute's end sums the rest up
      return;
    }
    if (slot->used && (!r.used || r.since < slot->since)) slot = &r;
  }
  if (slot->used) sum_up(*slot);  // the oldest gives way
  *slot = Repeat{true, e.what, e.front, e.outcome, args, e.peer, now_, 0};
  // The numbers and the client first, in small buffers: this runs under
  // the Pico W's lwIP callbacks, on their 4 KB stack.
  char numbers[40] = "";
  int n = 0;
  if (!std::isnan(e.az_deg))
    n = std::snprintf(numbers, sizeof numbers, " az %.1f", double{e.az_deg});
  if (!std::isnan(e.el_deg) && n >= 0 && n < static_cast<int>(sizeof numbers))
    std::snprintf(numbers + n, sizeof numbers - n, " el %.1f", double{e.el_deg});
  char client[access::kAddressTextBytes + 3];
  write("command %.*s%s%.*s%s from %.*s%s: %.*s", static_cast<int>(e.what.size()), e.what.data(),
        e.args.empty() ? "" : " ", static_cast<int>(e.args.size()), e.args.data(), numbers,
        static_cast<int>(e.front.size()), e.front.data(), client_text(e.peer, client),
        static_cast<int>(e.outcome.size()), e.outcome.data());
}

void CommandLog::sum_up(Repeat& r) {
  r.used = false;
  if (r.count == 0) return;
  char client[access::kAddressTextBytes + 3];
  write("command %.*s from %.*s%s: %.*s, %lu more in the last minute",
        static_cast<int>(r.what.size()), r.what.data(), static_cast<int>(r.front.size()),
        r.front.data(), client_text(r.peer, client), static_cast<int>(r.outcome.size()),
        r.outcome.data(), static_cast<unsigned long>(r.count));
}

void CommandLog::poll(Millis now) {
  // The repeats due are summed up in the minute that ends with them, then
  // the budget's minute rolls and says what it held back.
  for (Repeat& r : repeats_)
    if (r.used && now - r.since >= kWindowMs) sum_up(r);
  now_ = now;
  if (const std::uint32_t over = budget_.take_over(now); over > 0)
    write("%lu more command lines in the last minute, over the command log's budget",
          static_cast<unsigned long>(over));
}

void CommandLog::write(const char* format, ...) {
  if (!budget_.admit(now_)) return;
  char line[176];
  std::va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(line, sizeof line, format, args);
  va_end(args);
  if (n > 0)
    out_.write(std::string_view(line, n < static_cast<int>(sizeof line) ? n : sizeof line - 1));
}

}  // namespace rotord::command
