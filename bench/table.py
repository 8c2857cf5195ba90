"""Prints results.json rows as readable tables (used by run.py and compare.py)."""


def fmt(v):
    if v is None:
        return "-"
    if isinstance(v, float) and v != int(v):
        return f"{v:.3g}" if abs(v) < 100 else f"{v:.0f}"
    return str(int(v))


def print_control(rows):
    # control/<controller>/<profile>/<scenario>: one line per profile and
    # scenario, the controllers side by side.
    by_key = {}
    controllers = []
    for r in rows:
        _, who, profile, scenario = r["name"].split("/")
        if who not in controllers:
            controllers.append(who)
        by_key.setdefault((profile, scenario), {})[who] = r["metrics"]
    print("\nControl quality (simulator, virtual time): efficiency = bound / settle time;"
          " err = final error deg; corr = extra motor starts; sw = relay switchings")
    head = f"{'profile':7} {'scenario':13} {'bound_s':>8}"
    for c in controllers:
        head += f" | {c + ' eff':>13} {'err':>5} {'corr':>4} {'sw':>3}"
    print(head)
    for (profile, scenario), m in by_key.items():
        first = next(iter(m.values()))
        line = f"{profile:7} {scenario:13} {fmt(first['bound_s']):>8}"
        for c in controllers:
            x = m.get(c)
            if x is None:
                line += f" | {'':>13} {'':>5} {'':>4} {'':>3}"
                continue
            line += (f" | {fmt(x['efficiency']):>13} {x['final_error_deg']:>5.2f}"
                     f" {fmt(x['corrections']):>4} {fmt(x['relay_switchings']):>3}")
        print(line)


def print_commissioning(rows):
    # commissioning/<profile>/seed<N> (the run) and .../seed<N>/<scenario>
    # (a move row with the hand-tuned and the proposed settings).
    print("\nSelf-commissioning (simulator, virtual time): seed 0 = the nominal plant,"
          " 1..6 perturbed; eff = bound / settle time, hand = the profile's settings"
          " (pot calibrated right), prop = the proposed settings; * = proposed worse")
    for r in rows:
        parts = r["name"].split("/")
        m = r["metrics"]
        if len(parts) == 3:
            if m.get("failed"):
                print(f"{parts[1]:6} {parts[2]:6} FAILED")
                continue
            print(f"{parts[1]:6} {parts[2]:6} swapped {fmt(r['inputs']['swapped'])}"
                  f" rotator {m['rotator_s']:.0f} s, speed err {m['speed_error_pct']:.2f} %,"
                  f" coast err {m['coast_error_pct']:.1f} %, proposes tolerance"
                  f" {m['proposed_tolerance_deg']:.2f} deg, slow zone {m['proposed_slow_zone_deg']:.1f}"
                  f" deg, coast {m['proposed_coast_s']:.3f} s; rows worse {fmt(m['rows_worse'])}"
                  f" of {fmt(m['rows'])}, worst eff change {m['worst_efficiency_change']:+.2f},"
                  f" max err hand {m['hand_max_error_deg']:.2f} prop {m['proposed_max_error_deg']:.2f}")
        else:
            mark = "*" if m["proposed_worse"] else " "
            print(f"  {parts[1]:6} {parts[2]:6} {parts[3]:13} eff hand {m['hand_efficiency']:.2f}"
                  f" prop {m['proposed_efficiency']:.2f} | err hand {m['hand_final_error_deg']:.2f}"
                  f" prop {m['proposed_final_error_deg']:.2f} | corr hand {fmt(m['hand_corrections'])}"
                  f" prop {fmt(m['proposed_corrections'])} {mark}")


def print_generic(title, rows):
    print(f"\n{title}")
    for r in rows:
        inputs = " ".join(f"{k}={fmt(v)}" for k, v in r["inputs"].items())
        metrics = " ".join(f"{k}={fmt(v)}" for k, v in r["metrics"].items())
        print(f"  {r['name']:42} {metrics}   [{inputs}]")


def print_all(results):
    control = [r for r in results if r["name"].startswith("control/")]
    if control:
        print_control(control)
    commissioning = [r for r in results if r["name"].startswith("commissioning/")]
    if commissioning:
        print_commissioning(commissioning)
    sections = {}
    for r in results:
        if not r["name"].startswith(("control/", "commissioning/")):
            sections.setdefault(r["name"].split("/")[0], []).append(r)
    for title, rows in sections.items():
        print_generic(title, rows)
