#!/usr/bin/env python3
"""Prints the differences between two results.json files.

usage: bench/compare.py OLD.json NEW.json [--all] [--threshold PCT]

For every row name present in either file, each metric whose value changed
by more than the threshold (default 1 %) is printed with old, new and the
relative change; rows or metrics present in only one file are listed too.
Exit status 0 whatever the differences (it reports, it does not judge).
"""
import argparse
import json


def load(path):
    with open(path) as f:
        return {r["name"]: r for r in json.load(f)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--threshold", type=float, default=1.0, help="percent change to report")
    ap.add_argument("--all", action="store_true", help="print unchanged metrics too")
    args = ap.parse_args()
    old, new = load(args.old), load(args.new)
    changed = 0
    for name in list(old) + [n for n in new if n not in old]:
        if name not in new:
            print(f"- {name} (only in {args.old})")
            continue
        if name not in old:
            print(f"+ {name} (only in {args.new})")
            continue
        if old[name]["inputs"] != new[name]["inputs"]:
            print(f"! {name}: inputs differ {old[name]['inputs']} -> {new[name]['inputs']}")
        om, nm = old[name]["metrics"], new[name]["metrics"]
        for key in list(om) + [k for k in nm if k not in om]:
            a, b = om.get(key), nm.get(key)
            if a is None or b is None:
                if a != b:
                    print(f"  {name} {key}: {a} -> {b}")
                    changed += 1
                continue
            pct = (b - a) / abs(a) * 100.0 if a != 0 else (0.0 if b == 0 else float("inf"))
            if abs(pct) > args.threshold or args.all:
                print(f"  {name} {key}: {a:.6g} -> {b:.6g} ({pct:+.1f} %)")
                changed += 1
    print(f"{changed} metric(s) differ by more than {args.threshold} %")


if __name__ == "__main__":
    main()
