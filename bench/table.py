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
    sections = {}
    for r in results:
        if not r["name"].startswith("control/"):
            sections.setdefault(r["name"].split("/")[0], []).append(r)
    for title, rows in sections.items():
        print_generic(title, rows)
