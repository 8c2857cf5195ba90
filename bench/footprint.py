"""Footprint and cost: the core's flash and static RAM on the Cortex-M0+
(tests/embedded's size report: build-embedded, arm-none-eabi), and the
instructions one control tick executes under callgrind (valgrind), a count
that repeats from run to run, unlike a time."""
import os
import re
import shutil
import subprocess

TICKS = 6000  # 60 s of virtual time: a g5500 go-to (300, 60), moving then idle


def callgrind_instructions(build_dir, mode):
    out = os.path.join(build_dir, "bench", f"callgrind.{mode[2:]}.out")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                    os.path.join(build_dir, "bench", "rotord_bench"), mode, str(TICKS)],
                   check=True, capture_output=True)
    with open(out) as f:
        for line in f:
            if line.startswith("summary:") or line.startswith("totals:"):
                return int(line.split()[1])
    raise RuntimeError("no callgrind summary")


def tick_rows(build_dir):
    if shutil.which("valgrind") is None:
        raise RuntimeError("valgrind not installed (scripts/install-deps.sh)")
    with_tick = callgrind_instructions(build_dir, "--ticks")
    sim_only = callgrind_instructions(build_dir, "--sim-only")
    return [{"name": "footprint/tick_instructions",
             "inputs": {"ticks": TICKS, "profile_g5500": 1},
             "metrics": {"instructions_per_tick": (with_tick - sim_only) / TICKS}}]


# What the size report needs from the embedded preset: the probe and the
# empty baseline (they pull in every core layer). rotord_core itself is an
# INTERFACE library, so no build system has a target of that name.
M0_TARGETS = ["m0_size_probe", "m0_size_baseline"]


def _run(cmd, **kw):
    """Runs cmd; on failure raises RuntimeError naming the command and its
    last lines of output (they were captured, so say them here)."""
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        tail = "\n".join((r.stdout + r.stderr).strip().splitlines()[-8:])
        raise RuntimeError(f"`{' '.join(cmd)}` failed (exit {r.returncode}):\n{tail}")
    return r.stdout


def configure_embedded(src, binary_dir=None):
    """Configures the embedded preset (ccache when present); returns its env."""
    if shutil.which("arm-none-eabi-gcc") is None:
        raise RuntimeError("the embedded preset needs arm-none-eabi-gcc (scripts/install-deps.sh)")
    env = dict(os.environ, CCACHE_BASEDIR="/work", CCACHE_NOHASHDIR="true")
    launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"] \
        if shutil.which("ccache") else []
    where = ["-B", binary_dir] if binary_dir else []
    _run(["cmake", "--preset", "embedded", *where, *launcher], cwd=src, env=env)
    return env


def check_m0_targets(src, binary_dir):
    """Configures the embedded preset into binary_dir and checks that every
    target m0_rows() builds exists there (tests/packaging's bench check)."""
    configure_embedded(src, binary_dir)
    for target in M0_TARGETS:
        _run(["ninja", "-C", binary_dir, "-t", "query", target])


def m0_rows():
    """Configures the embedded preset and builds only what the size report
    needs (ccache makes reruns quick)."""
    src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = configure_embedded(src)
    _run(["cmake", "--build", "--preset", "embedded", "-j2", "--target", *M0_TARGETS], cwd=src,
         env=env)
    out = subprocess.run(["ctest", "--preset", "embedded", "-R", "^m0_size_budget$", "-V"],
                         cwd=src, env=env, capture_output=True, text=True).stdout
    metrics = {}
    for name, value, budget in re.findall(r"(\w+_(?:flash|ram)) = (\d+) of (\d+)", out):
        metrics[name + "_bytes"] = int(value)
        metrics[name + "_budget_bytes"] = int(budget)
    if not metrics:
        raise RuntimeError("size report not found in the output of "
                           "`ctest --preset embedded -R ^m0_size_budget$`")
    return [{"name": "footprint/core_m0plus", "inputs": {"minsizerel": 1}, "metrics": metrics}]


# The map page (issue 26): what a browser loads for /map.html, and what the
# map adds to the embedded assets (the Pico W's flash holds these same gzip
# -9 bytes, core/web/embed_assets.cmake).
MAP_PAGE = ["map.html", "style.css", "common.js", "access.js", "world.js", "map_draw.js",
            "places.js", "map.js"]
MAP_ADDED = ["world.js", "map_draw.js", "places.js", "map.js", "map.html"]


def web_rows(build_dir):
    src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    generated = os.path.join(build_dir, "core", "web_generated")

    def sizes(name):
        path = os.path.join(src, "web", name)
        if not os.path.exists(path):
            path = os.path.join(generated, name)
        with open(path, "rb") as f:
            raw = f.read()
        packed = subprocess.run(["gzip", "-9", "-n", "-c"], input=raw, capture_output=True,
                                check=True).stdout
        return len(raw), len(packed)

    world_raw, world_gz = sizes("world.js")
    page = [sizes(n) for n in MAP_PAGE]
    added = [sizes(n) for n in MAP_ADDED]
    everything = [sizes(n) for n in sorted(os.listdir(os.path.join(src, "web")))
                  if n.rsplit(".", 1)[-1] in ("html", "css", "js", "svg")] + [(world_raw, world_gz)]
    return [{"name": "footprint/web_map", "inputs": {"natural_earth_110m": 1},
             "metrics": {"world_js_raw_bytes": world_raw, "world_js_gzip_bytes": world_gz,
                         "map_page_raw_bytes": sum(r for r, _ in page),
                         "map_page_gzip_bytes": sum(g for _, g in page),
                         "map_added_flash_bytes": sum(g for _, g in added),
                         "web_assets_flash_bytes": sum(g for _, g in everything)}}]


def run(build_dir):
    # The M0+ size report is part of make bench: a failure fails the bench
    # (run.py), naming what was missing or which step broke.
    try:
        m0 = m0_rows()
    except (OSError, RuntimeError) as e:
        raise RuntimeError(f"M0+ size report (embedded preset): {e}") from e
    return tick_rows(build_dir) + web_rows(build_dir) + m0


if __name__ == "__main__":
    import sys
    if len(sys.argv) == 3 and sys.argv[1] == "--check-m0-targets":
        check_m0_targets(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), sys.argv[2])
        print("embedded preset: " + ", ".join(M0_TARGETS) + " configured")
    else:
        sys.exit("usage: footprint.py --check-m0-targets BINARY_DIR")
