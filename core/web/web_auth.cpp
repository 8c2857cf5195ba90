#include "web/web_auth.hpp"

#include <cstdio>
#include <cstring>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::web {
namespace {

/// "Bearer <token>" (scheme case-insensitive); empty for anything else.
std::string_view bearer_token(std::string_view authorization) {
  constexpr std::string_view kScheme = "Bearer";
  if (authorization.size() <= kScheme.size() ||
      !text::iequals(text::slice(authorization, 0, kScheme.size()), kScheme) ||
      authorization[kScheme.size()] != ' ')
    return {};
  std::string_view token = text::slice(authorization, kScheme.size() + 1);
  while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
  return token;
}

}  // namespace

bool WebAuth::enabled(const settings::Settings& settings) {
  return !settings.text(settings::Id::kWebPassword).empty();
}

Caller WebAuth::identify(const HttpRequest& request, const settings::Settings& settings,
                         Millis now) {
  Caller caller;
  if (config_.crypto == nullptr) return caller;
  access::Crypto& crypto = *config_.crypto;
  if (!request.authorization.empty()) {
    // A token presented is the identity, whatever cookie comes with it.
    caller.kind = Caller::Kind::kBadToken;
    const std::string_view token = bearer_token(request.authorization);
    std::array<std::uint8_t, access::TokenRecord::kHashBytes> hash{};
    if (token.size() != access::kTokenTextBytes || !access::hash_token(crypto, token, hash))
      return caller;
    for (std::size_t n = 0; n < std::size(kTokenRows); ++n) {
      access::TokenRecord record;
      const bool stored = access::parse_token_record(settings.text(kTokenRows[n]), record);
      // Compared with every row, each in constant time.
      if (crypto.equal(record.hash, hash) && stored) {
        caller.kind = Caller::Kind::kToken;
        caller.token = static_cast<int>(n);
        caller.scope = record.scope;
        std::memcpy(caller.token_name, record.name, sizeof caller.token_name);
        caller.holder.kind = access::LockHolder::Kind::kToken;
        std::memcpy(caller.holder.key.data(), record.hash.data(), caller.holder.key.size());
        std::memcpy(caller.holder.label, record.name, sizeof caller.holder.label);
      }
    }
    return caller;
  }
  if (request.cookie.empty()) return caller;
  const int session = sessions_.find(crypto, request.cookie, now);
  if (session < 0) return caller;
  caller.kind = Caller::Kind::kSession;
  caller.session = session;
  caller.logged_in = sessions_.at(session).authenticated;
  caller.holder.kind = access::LockHolder::Kind::kSession;
  std::memcpy(caller.holder.key.data(), sessions_.at(session).id.data(), caller.holder.key.size());
  return caller;
}

void WebAuth::write_line(const char* format, std::va_list args) {
  char line[160];
  const int n = std::vsnprintf(line, sizeof line - 1, format, args);
  if (n <= 0) return;
  std::size_t len =
      static_cast<std::size_t>(n) < sizeof line - 1 ? static_cast<std::size_t>(n) : sizeof line - 2;
  line[len++] = '\n';
  config_.log->write(std::string_view(line, len));
}

void WebAuth::write_summary(const access::LogGate::Summary& s) {
  char text[96];
  print("rotord: %s", access::LogGate::summary_text(s, text, sizeof text));
}

void WebAuth::print(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  write_line(format, args);
  va_end(args);
}

void WebAuth::log(const char* format, ...) {
  if (config_.log == nullptr || !gate().admit_line(now_)) return;
  std::va_list args;
  va_start(args, format);
  write_line(format, args);
  va_end(args);
}

void WebAuth::refused(const access::Peer& from, const char* format, ...) {
  if (config_.log == nullptr) return;
  access::LogGate::Summary evicted;
  const bool write = gate().admit(from, now_, evicted);
  if (evicted.count > 0) write_summary(evicted);
  if (!write) return;
  std::va_list args;
  va_start(args, format);
  write_line(format, args);
  va_end(args);
}

void WebAuth::flush_log(Millis now) {
  now_ = now;
  if (config_.log == nullptr) return;
  for (access::LogGate::Summary s = gate().next_due(now); s.count > 0; s = gate().next_due(now))
    write_summary(s);
}

std::uint32_t WebAuth::start(JobKind kind, std::string_view password,
                             const access::PasswordHash& target, const access::Peer& peer,
                             int session) {
  if (busy() || config_.crypto == nullptr || kind == JobKind::kNone) return 0;
  job_ = Job{};
  job_.kind = kind;
  job_.ticket = next_ticket_++;
  if (next_ticket_ == 0) next_ticket_ = 1;
  job_.peer = peer;
  job_.session = session;
  job_.target = target;
  pbkdf2_.start(password, target.salt, target.iterations);
  if (pbkdf2_.status() != access::Pbkdf2::Status::kRunning) {
    job_.computed = true;
    job_.failed = true;
  }
  return job_.ticket;
}

void WebAuth::step(std::uint32_t iterations) {
  if (job_.kind == JobKind::kNone || job_.computed || config_.crypto == nullptr) return;
  const access::Pbkdf2::Status s = pbkdf2_.step(*config_.crypto, iterations);
  if (s == access::Pbkdf2::Status::kRunning) return;
  job_.computed = true;
  job_.failed = s != access::Pbkdf2::Status::kDone;
}

}  // namespace rotord::web
