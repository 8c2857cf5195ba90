#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Issue 22's rows: real ISS passes (SGP4) over stations chosen for a
/// maximum elevation of 30/60/75/85 deg, one through north and one flipped,
/// on the g5500 and spid profiles, each followed by the on-board tracking
/// mode and by the modelled clients (bench/tracker_clients.hpp: Gpredict,
/// the SatNOGS client, a SatDump-like one) through a rotctld session, the
/// clients with the lead rule (track.stream_lead) off and on, all in one
/// run. Rows `clients/<profile>/<pass>/<who>`.
std::vector<Result> run_client_passes();

}  // namespace rotord::bench
