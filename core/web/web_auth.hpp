#pragma once
// Web and REST access control (docs/security.md), the parts that are not
// endpoints: who a request comes from (a login session's cookie, a bearer
// token, nobody), the sessions, failed-login limits, and the one slow-hash
// job (a login being checked, a new password being hashed) that the port
// advances a slice at a time so the control tick never waits for it.
#include <cstdarg>
#include <cstdint>

#include "access/api_token.hpp"
#include "access/control_lock.hpp"
#include "access/guess_budget.hpp"
#include "access/log_gate.hpp"
#include "access/login_limiter.hpp"
#include "access/password_hash.hpp"
#include "access/pbkdf2.hpp"
#include "access/peer.hpp"
#include "access/web_sessions.hpp"
#include "protocol/session.hpp"
#include "settings/settings.hpp"
#include "web/http_request.hpp"

namespace rotord::web {

/// Who sent a request.
struct Caller {
  enum class Kind : std::uint8_t {
    kNobody,    ///< no session cookie, no token
    kSession,   ///< a live session's cookie (logged in, or anonymous: see below)
    kToken,     ///< a valid bearer token
    kBadToken,  ///< an Authorization header that names no token
  };
  Kind kind = Kind::kNobody;
  int session = -1;        ///< kSession: the index in WebSessions
  bool logged_in = false;  ///< kSession: the session came from a login
  int token = -1;          ///< kToken: 0..3, web.token_<n+1>
  access::Scope scope = access::Scope::kRead;
  char token_name[access::TokenRecord::kMaxNameBytes + 1] = {};
  access::LockHolder holder;  ///< kSession or kToken: as the control lock names it

  /// With access control on: may read (GET) / command / manage access
  /// (password, tokens, access rules and secrets: the web login only).
  bool may_read() const { return logged_in || kind == Kind::kToken; }
  bool may_control() const {
    return logged_in || (kind == Kind::kToken && scope == access::Scope::kControl);
  }
  bool may_administer() const { return logged_in; }
  bool can_hold_lock() const { return kind == Kind::kSession || kind == Kind::kToken; }
};

class WebAuth {
 public:
  struct Config {
    /// nullptr: no cryptography on this port; a set password then locks
    /// everything but STOP (fail closed).
    access::Crypto* crypto = nullptr;
    /// PBKDF2 iterations of a new password hash, and per slice.
    std::uint32_t pbkdf2_iterations = 100'000;
    std::uint32_t pbkdf2_slice = 10'000;
    /// Where failed logins and access changes are logged (one line each); may be nullptr.
    protocol::ByteSink* log = nullptr;
    /// The process's log budget, shared with every other line the process
    /// logs (access/log_gate.hpp); nullptr: a budget of the web's own.
    access::LogGate* gate = nullptr;
  };

  explicit WebAuth(const Config& config) : config_(config) {}

  /// Access control is on: web.password holds a hash.
  static bool enabled(const settings::Settings& settings);

  /// Reads the request's Cookie and Authorization headers.
  Caller identify(const HttpRequest& request, const settings::Settings& settings, Millis now);

  access::Crypto* crypto() { return config_.crypto; }
  const Config& config() const { return config_; }
  access::WebSessions& sessions() { return sessions_; }
  const access::WebSessions& sessions() const { return sessions_; }
  access::LoginLimiter& limiter() { return limiter_; }
  /// Password guesses checked per class of client, each class together
  /// (access/guess_budget.hpp): strangers (every address not below), the
  /// addresses on access.control_networks, and browsers with a device cookie
  /// (access/device_cookie.hpp). Strangers' guesses, from however many
  /// addresses, never use the owner's budget.
  enum class Guesser : std::uint8_t { kStranger, kListed, kDevice };
  access::GuessBudget& budget(Guesser who) { return budgets_[static_cast<std::size_t>(who)]; }

  /// One line to the log (printf-style, no newline), within the log's
  /// budget of lines a minute (access/log_gate.hpp).
  void log(const char* format, ...) __attribute__((format(printf, 2, 3)));
  /// A refusal or error caused by `from` (a wrong password, an unknown
  /// token): the first in a minute is written, the rest summed up in one
  /// line when the minute ends, so no client can flood the log.
  void refused(const access::Peer& from, const char* format, ...)
      __attribute__((format(printf, 3, 4)));
  /// The port's clock, and the summaries that are due (Api::poll).
  void flush_log(Millis now);

  // --- The slow-hash job (one at a time) ---
  enum class JobKind : std::uint8_t { kNone, kLogin, kSetPassword };
  struct Job {
    JobKind kind = JobKind::kNone;
    std::uint32_t ticket = 0;
    access::Peer peer;
    int session = -1;             ///< kSetPassword: the requester's session, or -1
    access::PasswordHash target;  ///< kLogin: the stored hash; kSetPassword: the new salt and count
    bool computed = false;        ///< the PBKDF2 finished (or failed)
    bool failed = false;          ///< the crypto failed
    bool completed = false;       ///< the API acted on the result
    bool claimed = false;         ///< the response went out (or its client left)
    int status = 0;               ///< completed: the HTTP status to answer
    const char* message = "";     ///< completed: the error, or ""
    int new_session = -1;         ///< completed: the session whose cookie to set
    bool trusted = false;         ///< kLogin from a listed address or a recognised browser
  };
  /// Whether a job is running or its response has not gone out yet.
  bool busy() const { return job_.kind != JobKind::kNone && !(job_.completed && job_.claimed); }
  /// Starts one; returns its ticket, 0 when busy or without crypto.
  std::uint32_t start(JobKind kind, std::string_view password, const access::PasswordHash& target,
                      const access::Peer& peer, int session);
  /// A stranger's login being checked gives way to a trusted one (the owner
  /// gets in during an attack): it is dropped, and its client answered 503
  /// busy (Api::finish_pending). False when the job is not a stranger's login.
  bool preempt_for_trusted() {
    if (job_.kind != JobKind::kLogin || job_.trusted || job_.completed) return false;
    job_ = Job{};
    return true;
  }
  /// Runs up to `iterations` PBKDF2 iterations of the job (the port's slice).
  void step(std::uint32_t iterations);
  Job& job() { return job_; }
  const Job& job() const { return job_; }
  /// The derived key once computed.
  const access::Sha256Digest& derived_key() const { return pbkdf2_.key(); }

  /// Counters for logs and metrics.
  std::uint32_t failed_logins() const { return failed_logins_; }
  std::uint32_t refused_requests() const { return refused_requests_; }
  void count_failed_login() { ++failed_logins_; }
  void count_refused() { ++refused_requests_; }

 private:
  void write_line(const char* format, std::va_list args) __attribute__((format(printf, 2, 0)));
  void write_summary(const access::LogGate::Summary& s);
  void print(const char* format, ...) __attribute__((format(printf, 2, 3)));

  Config config_;
  access::WebSessions sessions_;
  access::LoginLimiter limiter_;
  access::GuessBudget budgets_[3];
  access::LogGate own_gate_;
  access::LogGate& gate() { return config_.gate != nullptr ? *config_.gate : own_gate_; }
  Millis now_ = 0;
  access::Pbkdf2 pbkdf2_;
  Job job_;
  std::uint32_t next_ticket_ = 1;
  std::uint32_t failed_logins_ = 0;
  std::uint32_t refused_requests_ = 0;
};

/// The web.token_<n> rows, in order.
inline constexpr settings::Id kTokenRows[] = {settings::Id::kWebToken1, settings::Id::kWebToken2,
                                              settings::Id::kWebToken3, settings::Id::kWebToken4};

}  // namespace rotord::web
