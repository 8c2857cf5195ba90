#include "clock_control.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "log.hpp"

namespace rotord::linux_port {

ClockControl::ClockControl(asio::io_context& io, Advance advance)
    : io_(io), in_(io, ::dup(STDIN_FILENO)), advance_(std::move(advance)) {}

void ClockControl::start() {
  read_next();
}

void ClockControl::read_next() {
  asio::async_read_until(in_, asio::dynamic_buffer(buffer_, 4096), '\n',
                         [this](std::error_code ec, std::size_t n) {
                           if (ec) {
                             // End of input: the clock stays where it is.
                             if (ec != asio::error::operation_aborted)
                               log::warn("clock control input closed");
                             return;
                           }
                           std::string line = buffer_.substr(0, n - 1);
                           buffer_.erase(0, n);
                           handle(line);
                           read_next();
                         });
}

void ClockControl::handle(const std::string& line) {
  Millis ms = 0;
  if (line.rfind("advance ", 0) == 0) {
    char* end = nullptr;
    const long long v = std::strtoll(line.c_str() + 8, &end, 10);
    if (end == line.c_str() + 8 || *end != '\0' || v < 0 || v > kMaxAdvanceMs) {
      log::warn("clock: 'advance' takes 0..%lld ms", static_cast<long long>(kMaxAdvanceMs));
      return;
    }
    ms = v;
  } else if (line != "now") {
    log::warn("clock: unknown command (advance <ms>, now)");
    return;
  }
  // A client's command written before this line (a Hamlib rotctl that sent
  // an Easycomm set, which has no reply, and exited) must act before the
  // clock moves. Its bytes are already in a socket buffer, but the loop may
  // have seen stdin first: let the handlers already queued run (an accept,
  // then the speculative read it starts) before advancing.
  after_queued_handlers(kHandlerHops, [this, ms] {
    const Millis now = advance_(ms);
    log::reply("clock %lld", static_cast<long long>(now));
  });
}

void ClockControl::after_queued_handlers(int hops, std::function<void()> fn) {
  if (hops == 0) return fn();
  asio::post(io_, [this, hops, fn = std::move(fn)]() mutable {
    after_queued_handlers(hops - 1, std::move(fn));
  });
}

}  // namespace rotord::linux_port
