"""The Pico W firmware on an emulated RP2040 (make hil): the CPU cycles per
10 ms control tick period of the whole loop, at rest and during go-tos, and
the most heap malloc used in any scenario of the room the static RAM leaves,
how long after the wind had held for wind.hold_s the stow began and how
long after a gust began to turn the mast the slip was flagged, as
the last `make hil` measured them (build/bench/hil_<board>.json, one file
per image: pico_w, pico). Emulation takes
minutes and needs the pico-sdk and a bootrom, so this part reports the file
rather than running it."""
import json
import os

from skip import Skipped


def run(build_dir):
    bench = os.path.join(build_dir, "bench")
    names = sorted(n for n in os.listdir(bench) if n.startswith("hil_") and n.endswith(".json")) \
        if os.path.isdir(bench) else []
    if not names:
        raise Skipped(f"no {bench}/hil_*.json: run `make hil` (needs PICO_SDK_PATH and "
                           "ROTORD_RP2040_BOOTROM)")
    rows = []
    for name in names:
        with open(os.path.join(bench, name)) as f:
            rows.extend(json.load(f))
    return rows
