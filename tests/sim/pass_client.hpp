#pragma once
// What the Gpredict-style clients of the tracking scenarios (the continuity
// rule, recognising a client's pass) share: a cycle of 1 s over the ISS's
// pass through north, and the `p` and `P az el` they send through rotctld.
// Each client keeps its own frame and its own measurement.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "../unit/iss_elements.hpp"
#include "../unit/string_sink.hpp"
#include "pass_bench.hpp"
#include "protocol/rotctld_session.hpp"
#include "tracking/sky_target.hpp"
#include "tracking/tle.hpp"

namespace rotord::testing {

/// Gpredict's cycle as its source reads (gtk-rot-ctrl.c): once a second the
/// ISS's look angles from the bench's station, then a second of the bench's
/// time. From AOS to LOS (at most 1200 cycles), `cycle(n, look)` runs with the
/// cycle's number (counted from the first, before AOS) and may end the pass
/// there (false), before that second runs.
template <typename Cycle>
void each_second_of_the_iss_pass(PassBench& b, Cycle cycle) {
  tracking::Tle tle;
  EXPECT_TRUE(tracking::parse_tle(kIssLine1, kIssLine2, tle).ok());
  tracking::SkyTarget sat;
  EXPECT_EQ(sat.set_satellite(tle), tracking::Sgp4Error::kOk);
  const tracking::Observer station = b.controller().observer();
  bool up = false;
  for (int n = 0; n < 1200; ++n) {
    tracking::LookAngles look;
    EXPECT_EQ(sat.look(*b.unix_ms(), station, look), tracking::Sgp4Error::kOk);
    if (look.el_deg < 0.0) {
      if (up) return;  // LOS
    } else {
      up = true;
      if (!cycle(n, look)) return;
    }
    b.run_ms(1000);
  }
}

/// The client's `p`: the position it reads back, in its frame.
inline void read_position(protocol::RotctldSession& client, double& az_deg, double& el_deg) {
  const std::string reply = ask(client, "p\n");
  EXPECT_EQ(std::sscanf(reply.c_str(), "%lf\n%lf", &az_deg, &el_deg), 2) << reply;
}

/// The client's `P az el`, to the hundredth as Gpredict prints it; whether
/// rotord took it.
inline bool send_goto(protocol::RotctldSession& client, double az_deg, double el_deg) {
  char cmd[64];
  std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", az_deg, el_deg);
  return ask(client, cmd) == "RPRT 0\n";
}

}  // namespace rotord::testing
