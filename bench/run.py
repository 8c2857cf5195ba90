#!/usr/bin/env python3
"""Runs every benchmark and writes build/bench/results.json.

results.json is a list of {"name", "inputs", "metrics"} rows with numbers
only, so two runs compare key by key (bench/compare.py OLD NEW). Each part
runs as its own program; a part that cannot run (a tool missing, a build
step failing) is reported by name, the others still run, and the bench then
exits non-zero. Benchmarks print numbers; no test asserts on
them.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import table  # noqa: E402
from skip import Skipped  # noqa: E402


def run_control(build_dir):
    out = os.path.join(build_dir, "bench", "control.json")
    subprocess.run([os.path.join(build_dir, "bench", "rotord_bench"), "--out", out], check=True)
    with open(out) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--build-dir", default="build")
    ap.add_argument("--only", default="", help="comma-separated parts: control,protocol,footprint,tracking,hil")
    args = ap.parse_args()
    parts = {
        "control": run_control,
    }
    try:
        import protocol_bench
        parts["protocol"] = protocol_bench.run
    except ImportError:
        pass
    try:
        import footprint
        parts["footprint"] = footprint.run
    except ImportError:
        pass
    try:
        import hil
        parts["hil"] = hil.run
    except ImportError:
        pass
    chosen = [p for p in args.only.split(",") if p] or list(parts)
    results = []
    failed = []
    for name in chosen:
        print(f"bench: {name} ...", file=sys.stderr, flush=True)
        try:
            results.extend(parts[name](args.build_dir))
        except Skipped as e:
            print(f"bench: {name} skipped: {e}", file=sys.stderr)
        except (OSError, subprocess.CalledProcessError, RuntimeError) as e:
            # The other parts still run; the bench then fails, naming this one.
            print(f"bench: {name} FAILED: {e}", file=sys.stderr)
            failed.append(name)
    path = os.path.join(args.build_dir, "bench", "results.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(results, f, indent=1)
        f.write("\n")
    table.print_all(results)
    print(f"\nwrote {path} ({len(results)} rows)")
    if failed:
        sys.exit(f"bench: failed: {', '.join(failed)} (see above)")


if __name__ == "__main__":
    main()
