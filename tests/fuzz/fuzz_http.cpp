// libFuzzer target: arbitrary requests into the HTTP session and REST API on a
// controller with fake hardware. The first byte picks whether the input is
// sent raw (framing, headers, chunking) or as the JSON body of one endpoint
// (so the JSON reader and every API handler see deep inputs, not just
// rejected request lines). Crashes, sanitizer reports and broken invariants
// (both relays on, an inconsistent settings table kept) fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "web/http_session.hpp"

namespace {

using rotord::fuzz::NullSink;

// Counts saves and keeps the document, so a save that fails is exercised too.
class FuzzStorage final : public rotord::hal::Storage {
 public:
  bool fail = false;
  long load(char*, std::size_t) override { return -1; }
  bool save(std::string_view) override { return !fail; }
};

class NoReboot final : public rotord::command::SystemHooks {
 public:
  const char* reboot() override { return nullptr; }
  const char* reboot_to_bootloader() override { return "not here"; }
};

constexpr std::string_view kPosts[] = {
    "/api/goto", "/api/move",     "/api/stop",           "/api/park",
    "/api/mode", "/api/settings", "/api/settings/reset", "/api/reboot",
};

std::string request_for(std::uint8_t selector, std::string_view body) {
  const std::string_view path = kPosts[selector % std::size(kPosts)];
  std::string r = "POST ";
  r.append(path);
  r.append(" HTTP/1.1\r\nHost: rotord\r\nContent-Type: application/json\r\nContent-Length: ");
  r.append(std::to_string(body.size()));
  r.append("\r\n\r\n");
  r.append(body);
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  rotord::testing::FakeRotator rotator;
  rotord::settings::Settings defaults = rotator.settings;
  FuzzStorage storage;
  storage.fail = (data[0] & 0x80) != 0;
  NoReboot reboot;
  rotord::web::Api api{
      rotord::web::ApiContext{*rotator.controller, &storage, &defaults, &reboot, "fuzz"}};
  rotord::web::HttpSession session(api);
  NullSink sink;

  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::string input = (data[0] & 0x40) != 0 ? std::string(rest) : request_for(data[0], rest);
  // Split at a data-dependent point with ticks in between: partial requests,
  // and API calls while the rotator moves.
  const std::size_t split = input.size() / 2 + (data[0] & 0x0f);
  const std::string_view all(input);
  session.receive(all.substr(0, split < all.size() ? split : all.size()), sink);
  rotator.run_ms(50);
  if (split < all.size()) session.receive(all.substr(split), sink);
  rotator.run_ms(50);
  session.poll(rotator.now, sink);

  rotord::fuzz::abort_on_both_directions(rotator);
  // Whatever was posted, the controller never keeps settings that break a rule.
  if (rotator.settings.check_consistency().error != rotord::Error::kOk) std::abort();
  return 0;
}
