#include "protocol/datagram.hpp"

#include <cstdarg>
#include <cstdio>

namespace rotord::protocol {

bool DatagramReplies::add(std::uint16_t port, const char* fmt, ...) {
  if (count_ == kMaxReplies) return false;
  Reply& r = items_[count_];
  std::va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(r.bytes.data(), r.bytes.size(), fmt, args);
  va_end(args);
  // snprintf keeps one byte for its NUL, which is not sent.
  if (n < 0 || static_cast<std::size_t>(n) >= r.bytes.size()) return false;
  r.port = port;
  r.size = static_cast<std::size_t>(n);
  ++count_;
  return true;
}

const char* outcome_name(DatagramOutcome outcome) {
  switch (outcome) {
    case DatagramOutcome::kDone:
      return "done";
    case DatagramOutcome::kNotForUs:
      return "for another rotor";
    case DatagramOutcome::kMalformed:
      return "malformed, ignored";
    case DatagramOutcome::kOversize:
      return "too long, ignored";
    case DatagramOutcome::kRefused:
      return "refused (read-only sender)";
    case DatagramOutcome::kFailed:
      return "refused by the controller";
  }
  return "?";
}

const char* outcome_label(DatagramOutcome outcome) {
  static constexpr const char* kLabels[kDatagramOutcomeCount] = {
      "done", "not_for_us", "malformed", "oversize", "refused", "failed"};
  const auto i = static_cast<std::size_t>(outcome);
  return i < kDatagramOutcomeCount ? kLabels[i] : "?";
}

}  // namespace rotord::protocol
