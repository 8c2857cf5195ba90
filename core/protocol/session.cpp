#include "protocol/session.hpp"

#include "rotator/controller.hpp"

namespace rotord::protocol {

bool Session::may_control(Controller& controller) const {
  return access::may_control(controller.settings(), peer_) && !controller.control_lock().held();
}

}  // namespace rotord::protocol
