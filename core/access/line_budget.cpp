#include "access/line_budget.hpp"

namespace rotord::access {

void LineBudget::roll(Millis now) {
  if (!started_) {
    started_ = true;
    window_start_ = now;
  }
  if (now - window_start_ < kWindowMs) return;
  window_start_ = now;
  lines_ = 0;
  dropped_ += dropping_;
  dropping_ = 0;
}

bool LineBudget::admit(Millis now) {
  roll(now);
  if (lines_ >= lines_per_window_) {
    ++dropping_;
    return false;
  }
  ++lines_;
  return true;
}

std::uint32_t LineBudget::take_over(Millis now) {
  roll(now);
  const std::uint32_t over = dropped_;
  dropped_ = 0;
  return over;
}

}  // namespace rotord::access
