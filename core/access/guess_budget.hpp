#pragma once
// How many password guesses the controller checks, for a whole class of
// clients together (strangers, the allow-listed addresses, recognised
// browsers): a rate with a small burst (the generic cell rate algorithm), so
// guessing from any number of addresses is as slow as from one
// (docs/security.md, "Failed logins").
#include <algorithm>

#include "util/time.hpp"

namespace rotord::access {

class GuessBudget {
 public:
  /// Checked guesses per minute in the long run.
  static constexpr Millis kIntervalMs = 6000;  // 10 a minute
  /// Guesses that may come at once after a quiet spell (a typo, then the
  /// right password).
  static constexpr Millis kBurst = 2;

  /// How long until a guess may be checked (0: now).
  Millis wait_ms(Millis now) const {
    const Millis allowed_at = next_ms_ - (kBurst - 1) * kIntervalMs;
    return std::max<Millis>(0, allowed_at - now);
  }
  /// A guess is being checked now (call only when wait_ms is 0).
  void spend(Millis now) { next_ms_ = std::max(next_ms_, now) + kIntervalMs; }

 private:
  Millis next_ms_ = 0;  ///< the theoretical time of the next guess at the steady rate
};

}  // namespace rotord::access
