#include "protocol/console_reply.hpp"

#include <cstdarg>

namespace rotord::protocol::console {

void send_line(ByteSink& out, const char* fmt, ...) {
  ConsoleSession::Reply reply(ConsoleSession::kReplyRules);
  std::va_list args;
  va_start(args, fmt);
  reply.vformat(fmt, args);
  va_end(args);
  reply.end_line();
  reply.send(out);
}

}  // namespace rotord::protocol::console
