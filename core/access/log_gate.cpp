#include "access/log_gate.hpp"

#include <cstdio>

namespace rotord::access {
namespace {

bool same(const Peer& a, const Peer& b) {
  return a.same_host(b);
}

}  // namespace

bool LogGate::admit_line(Millis now) {
  return budget_.admit(now);
}

bool LogGate::admit(const Peer& source, Millis now, Summary& evicted) {
  evicted = {};
  budget_.roll(now);
  Entry* slot = nullptr;
  for (Entry& e : entries_) {
    if (e.used && same(e.source, source)) slot = &e;
  }
  if (slot != nullptr && now - slot->since < kWindowMs) {
    ++slot->quiet;  // its minute's first line is out: counted, summed up later
    return false;
  }
  if (slot == nullptr) {
    // A free entry, else the one whose minute began first gives way.
    for (Entry& e : entries_) {
      if (!e.used) {
        slot = &e;
        break;
      }
      if (slot == nullptr || e.since < slot->since) slot = &e;
    }
  }
  if (slot->used && slot->quiet > 0) {
    // Its summary is a line like any other: many addresses taking turns
    // must not get a line each past the budget.
    if (admit_line(now)) {
      evicted = {slot->source, slot->quiet};
    } else {
      budget_.count_over(slot->quiet - 1);  // admit_line counted one
    }
  }
  *slot = Entry{true, source, now, 0};
  return admit_line(now);
}

LogGate::Summary LogGate::next_due(Millis now) {
  budget_.roll(now);
  for (Entry& e : entries_) {
    if (!e.used || e.quiet == 0 || now - e.since < kWindowMs) continue;
    const Summary s{e.source, e.quiet};
    e.quiet = 0;
    return s;
  }
  return {Peer{}, budget_.take_over(now)};
}

const char* LogGate::summary_text(const Summary& s, char* out, std::size_t size) {
  const auto count = static_cast<unsigned long>(s.count);
  if (s.source.kind == Peer::Kind::kUnknown) {
    std::snprintf(out, size, "%lu more log lines in the last minute, over the log's budget", count);
    return out;
  }
  char address[kAddressTextBytes];
  peer_text(s.source, address, true);
  std::snprintf(out, size, "%lu more from %s%s in the last minute", count, address,
                s.source.kind == Peer::Kind::kIpv6 ? "/64" : "");
  return out;
}

}  // namespace rotord::access
