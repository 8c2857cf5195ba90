#include "protocol/session.hpp"

#include "command/typed.hpp"

namespace rotord::protocol {

bool Session::may_control(Controller& controller, std::string_view what) const {
  return command::may_control(controller, origin(), what);
}

void drain_output(Session& session, ByteSink& out) {
  // Every call with unbounded room finishes the reply; the bound only keeps
  // a session that never does from hanging the transport.
  constexpr std::size_t kUnbounded = static_cast<std::size_t>(-1);
  for (int n = 0; n < 8 && session.output_pending(); ++n) session.write_more(kUnbounded, out);
}

}  // namespace rotord::protocol
