"""The Pico W firmware on an emulated RP2040 (make hil): the CPU cycles per
10 ms control tick period of the whole loop, at rest and during go-tos, as
the last `make hil` measured them (build/bench/hil.json). Emulation takes
minutes and needs the pico-sdk and a bootrom, so this part reports the file
rather than running it."""
import json
import os


def run(build_dir):
    path = os.path.join(build_dir, "bench", "hil.json")
    if not os.path.exists(path):
        raise RuntimeError(f"{path} not found: run `make hil` (needs PICO_SDK_PATH and "
                           "ROTORD_RP2040_BOOTROM)")
    with open(path) as f:
        return json.load(f)
