// libFuzzer target: access control's parsing paths with a web password set,
// a control token stored and a login session open: Cookie and Authorization
// headers, login/password/token/lock bodies, the stored hash and token
// formats. Crashes, sanitizer reports and one broken invariant fail: a
// request that carries neither the session's cookie nor the token never
// moves the rotator, changes a setting, or takes the lock.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "access/api_token.hpp"
#include "access/password_hash.hpp"
#include "access/web_sessions.hpp"
#include "fake_crypto.hpp"
#include "fake_rotator.hpp"
#include "web/http_session.hpp"

namespace {

struct NullSink final : rotord::protocol::ByteSink {
  void write(std::string_view) override {}
};

constexpr std::string_view kPaths[] = {
    "/api/login", "/api/logout", "/api/password", "/api/tokens", "/api/tokens/revoke",
    "/api/lock",  "/api/unlock", "/api/goto",     "/api/auth",   "/api/settings",
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  // The stored formats and the Cookie header on their own.
  rotord::access::PasswordHash hash;
  (void)rotord::access::parse_password_hash(rest, hash);
  rotord::access::TokenRecord record;
  (void)rotord::access::parse_token_record(rest, record);
  (void)rotord::access::cookie_value(rest, rotord::access::WebSessions::kCookieName);

  rotord::testing::FakeRotator rotator;
  rotord::settings::Settings defaults = rotator.settings;
  rotord::testing::FakeCrypto crypto;
  rotord::web::ApiContext context{*rotator.controller, nullptr, &defaults, nullptr, "fuzz"};
  context.crypto = &crypto;
  context.pbkdf2_iterations = 1000;
  context.pbkdf2_slice = 500;
  // A password ("fuzz password") and a control token, as a port stores them;
  // the hash once per process (it is the slow part).
  static const rotord::access::PasswordHash stored = [] {
    rotord::testing::FakeCrypto c;
    rotord::access::PasswordHash h;
    h.iterations = 1000;
    rotord::access::Pbkdf2 job;
    job.start("fuzz password", h.salt, h.iterations);
    while (job.step(c, 1000) == rotord::access::Pbkdf2::Status::kRunning) {
    }
    for (std::size_t n = 0; n < h.key.size(); ++n) h.key[n] = job.key()[n];
    return h;
  }();
  char text[96];
  rotord::access::format_password_hash(stored, text, sizeof text);
  rotator.settings.set_text(rotord::settings::Id::kWebPassword, text);
  char token[rotord::access::kTokenTextBytes + 1];
  rotord::access::TokenRecord tracker;
  std::memcpy(tracker.name, "tracker", 8);
  tracker.scope = rotord::access::Scope::kControl;
  rotord::access::make_token(crypto, token, tracker.hash);
  rotord::access::format_token_record(tracker, text, sizeof text);
  rotator.settings.set_text(rotord::settings::Id::kWebToken1, text);
  rotord::web::Api api{context};
  rotord::Millis now = 1000;
  api.poll(now);
  const int open = api.auth().sessions().create(crypto, now, 600000, true);
  char id[rotord::access::WebSessions::kIdTextBytes + 1];
  api.auth().sessions().id_text(open, id);
  const std::uint32_t revision = rotator.settings.revision();

  // Raw bytes, or a request to one endpoint with a fuzzed Cookie or
  // Authorization header (or the real ones) and a fuzzed body.
  std::string input;
  const std::uint8_t mode = data[0];
  if ((mode & 0x80) != 0) {
    input = std::string(rest);
  } else {
    const std::size_t cut = rest.empty() ? 0 : static_cast<std::uint8_t>(rest[0]) % rest.size();
    const std::string_view header = rest.substr(rest.empty() ? 0 : 1, cut);
    const std::string_view body =
        rest.substr(cut < rest.size() ? cut + (rest.empty() ? 0 : 1) : rest.size());
    input = "POST ";
    input.append(kPaths[(mode & 0x0f) % std::size(kPaths)]);
    input.append(" HTTP/1.1\r\nHost: rotord\r\nContent-Type: application/json\r\n");
    switch ((mode >> 4) & 0x07) {
      case 0:
        input.append("Cookie: ").append(header).append("\r\n");
        break;
      case 1:
        input.append("Authorization: ").append(header).append("\r\n");
        break;
      case 2:
        input.append("Authorization: Bearer ").append(header).append("\r\n");
        break;
      case 3:
        input.append("Cookie: rotord_session=").append(header).append("\r\n");
        break;
      case 4:
        input.append("Cookie: rotord_session=").append(id).append("\r\n");
        break;
      case 5:
        input.append("Authorization: Bearer ").append(token).append("\r\n");
        break;
      default:
        break;
    }
    input.append("Content-Length: ").append(std::to_string(body.size())).append("\r\n\r\n");
    input.append(body);
  }
  const bool credentialed = input.find(id) != std::string::npos ||
                            input.find(token) != std::string::npos ||
                            input.find("fuzz password") != std::string::npos;

  rotord::web::HttpSession session(api);
  session.set_peer(rotord::access::Peer::from_ipv4(0x0A000001));
  NullSink sink;
  session.receive(input, sink);
  for (int n = 0; n < 6; ++n) {
    now += 10;
    api.poll(now);
    session.poll(now, sink);
    rotator.run_ms(10);
  }

  if (!credentialed) {
    const rotord::RotatorStatus s = rotator.controller->status();
    if (s.az.has_target || s.moving()) std::abort();
    if (rotator.settings.revision() != revision) std::abort();
    if (rotator.controller->control_lock().held()) std::abort();
  }
  const auto& out = rotator.az.drive.last;
  if (out.on(rotord::OutputChannel::kRelayCw) && out.on(rotord::OutputChannel::kRelayCcw))
    std::abort();
  return 0;
}
