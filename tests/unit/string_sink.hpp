#pragma once
// Keeps every byte a session writes, and counts the writes: a transport sends
// each write as one unit (one TCP segment where it can).
#include <string>
#include <string_view>
#include <vector>

#include "protocol/session.hpp"

namespace rotord::testing {

struct StringSink final : protocol::ByteSink {
  std::string data;
  int writes = 0;
  void write(std::string_view bytes) override {
    data.append(bytes);
    ++writes;
  }
};

/// A log's side of a ByteSink: each write() is one line (the command log
/// writes one line a write).
struct LineSink final : protocol::ByteSink {
  std::vector<std::string> lines;
  void write(std::string_view bytes) override { lines.emplace_back(bytes); }
};

/// Sends `bytes` to a session and returns all it wrote back.
inline std::string ask(protocol::Session& session, std::string_view bytes) {
  StringSink out;
  session.receive(bytes, out);
  return out.data;
}

}  // namespace rotord::testing
