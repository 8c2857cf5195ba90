#pragma once
#include "util/time.hpp"

namespace rotord::net {

/// How long the Pico W's setup access point `rotord-setup` may stay open.
///
/// Without a password (wifi.ap_password empty) the AP lets anyone in radio
/// range reach the settings page, and with access control off the rotator.
/// It is what a new controller needs on its first boot, so it opens, but
/// only within `open_minutes` (wifi.ap_open_minutes) of power-on: a
/// controller whose home network is down for a day is not left open to the
/// street all that time. A phone already joined keeps it open (nobody is cut
/// off mid-setup); a WPA2 AP (a password set) has no limit; 0 minutes means
/// no limit. After the window a power cycle, which needs hands on the
/// hardware, opens it again.
struct SetupApPolicy {
  bool has_password = false;  ///< wifi.ap_password set: WPA2
  int open_minutes = 30;      ///< wifi.ap_open_minutes; 0: no limit

  /// The open AP may (still) be offered `since_boot_ms` after power-on with
  /// `stations` phones joined.
  bool may_offer(Millis since_boot_ms, int stations) const {
    if (has_password || open_minutes <= 0 || stations > 0) return true;
    return since_boot_ms < static_cast<Millis>(open_minutes) * 60'000;
  }
};

}  // namespace rotord::net
