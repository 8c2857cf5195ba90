#pragma once
// The control lock: one operator takes control for some minutes (POST
// /api/lock); everybody else is read-only until it is released or runs out:
// other web sessions and tokens get 423 Locked, and every line protocol
// refuses moves and setting changes in its own way (Session::may_control).
// STOP is never locked. It lives in the Controller, which every command
// source already holds, so no source can miss it.
#include <array>
#include <cstdint>
#include <cstring>

#include "util/time.hpp"

namespace rotord::access {

/// Who holds the lock: a web session or a REST token, named by bytes no
/// other session or token shares (the first bytes of a session's random id,
/// of a token's hash).
struct LockHolder {
  enum class Kind : std::uint8_t { kSession, kToken };
  Kind kind = Kind::kSession;
  std::array<std::uint8_t, 8> key{};
  /// The token's name, for GET /api/auth ("" for a web session).
  char label[17] = {};

  bool same(const LockHolder& other) const { return kind == other.kind && key == other.key; }
};

class ControlLock {
 public:
  /// The longest hold one request may ask for.
  static constexpr Millis kMaxHoldMs = 240 * 60 * 1000;

  bool held() const { return held_; }
  bool held_by(const LockHolder& who) const { return held_ && holder_.same(who); }
  const LockHolder& holder() const { return holder_; }
  /// When it runs out, on the transport's (wall) clock.
  Millis until() const { return until_; }

  void take(const LockHolder& who, Millis until) {
    holder_ = who;
    until_ = until;
    held_ = true;
  }
  void release() { held_ = false; }
  /// Releases it once its time is up; called by the web API's poll.
  void expire(Millis now) {
    if (held_ && now >= until_) held_ = false;
  }

 private:
  bool held_ = false;
  LockHolder holder_;
  Millis until_ = 0;
};

}  // namespace rotord::access
