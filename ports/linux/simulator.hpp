#pragma once
// The Linux daemon's one seam to the simulator (sim/): the only file of
// ports/ that includes it (core/layers.cmake names it as ROTORD_SIM_SEAM and
// the build's layer check refuses a sim/ include anywhere else in ports/).
// What the daemon uses of the simulator, all of it here:
//  - sim::Profile, sim::find_profile(), sim::all_profiles(): the rotators of
//    --sim, whose geometry is the profile layer of the settings
//    (print_config.hpp, legacy_profile_guess.hpp);
//  - sim::SimRotator: the simulated plant behind the hal interfaces under
//    --hw sim (daemon.hpp).
// The Pico W firmware uses none of it: its plant is real (or, under
// `make hil`, outside the firmware image).
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
