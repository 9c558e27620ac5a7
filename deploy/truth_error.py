#!/usr/bin/env python3
"""Client-side error against the truth (issue 6): joins what the zones say sampled entities
were (truth_<rank>.csv: tick, id, kind, x, y, z, written by zone_node --truth-every K) with
what the clients showed of them (display.csv: player, tick, id, order, x, y, z, distance,
written by client_stub --truth-every K) on (tick, id), and prints the distance's p50/p99/max per
dead-reckoning order, and per band of distance from the viewer (as the player drew itself).

Usage: deploy/truth_error.py RUN_DIR   (prints the table; --json prints the figures as JSON)
"""
import csv
import json
import math
import sys
from pathlib import Path

ORDERS = {0: "static", 1: "first", 2: "second"}
# Distance from the viewer (m): a budget holds error as an angle, so error grows with it.
BANDS = [(0, 25), (25, 50), (50, 100), (100, math.inf)]


def band_name(lo, hi):
    return f"{lo}-{hi} m" if hi != math.inf else f"{lo}+ m"


def band_of(distance):
    for lo, hi in BANDS:
        if lo <= distance < hi:
            return band_name(lo, hi)
    return None


def pct(v, p):
    v = sorted(v)
    return v[min(len(v) - 1, max(0, int(round(p / 100 * len(v) + 0.5)) - 1))] if v else 0.0


def load_truth(zone_dir):
    truth = {}
    for path in sorted(Path(zone_dir).glob("truth_*.csv")):
        with open(path) as f:
            for r in csv.DictReader(f):
                truth[(int(r["tick"]), int(r["id"]))] = (float(r["x"]), float(r["y"]), float(r["z"]))
    return truth


def join(zone_dir, display=None):
    """Per order and per distance band: the errors (m) of every shown sample with a truth;
    and the unmatched count. display defaults to zone_dir/display.csv (a run folder holds
    both). Bands leave out static entities and samples shown before the player saw itself."""
    truth = load_truth(zone_dir)
    errors, bands, unmatched = {}, {}, 0
    path = Path(display) if display else Path(zone_dir) / "display.csv"
    if not truth or not path.exists():
        return errors, bands, unmatched
    with open(path) as f:
        for r in csv.DictReader(f):
            t = truth.get((int(r["tick"]), int(r["id"])))
            if t is None:
                unmatched += 1  # a tick the zones did not reach, or shown after its despawn
                continue
            d = math.dist(t, (float(r["x"]), float(r["y"]), float(r["z"])))
            errors.setdefault(ORDERS.get(int(r["order"]), r["order"]), []).append(d)
            distance = float(r.get("distance", -1))
            if int(r["order"]) != 0 and distance >= 0:
                bands.setdefault(band_of(distance), []).append(d)
    return errors, bands, unmatched


def summary(v):
    return {"samples": len(v), "p50_m": pct(v, 50), "p99_m": pct(v, 99), "max_m": max(v)}


def figures(errors, bands, unmatched):
    order = [band_name(lo, hi) for lo, hi in BANDS]
    return {"unmatched": unmatched,
            "orders": {o: summary(v) for o, v in sorted(errors.items())},
            "bands": {b: summary(bands[b]) for b in order if b in bands}}


def print_table(fig, out=sys.stdout):
    print(f"client-side error against the zones' truth (joined by tick and id; "
          f"{fig['unmatched']} shown samples without a truth)", file=out)
    print(f"{'order':>8} {'samples':>9} {'p50 m':>8} {'p99 m':>8} {'max m':>8}", file=out)
    for o, f in fig["orders"].items():
        print(f"{o:>8} {f['samples']:>9} {f['p50_m']:>8.3f} {f['p99_m']:>8.3f} {f['max_m']:>8.3f}",
              file=out)
    if fig.get("bands"):
        print("moving entities by distance from the viewer", file=out)
        print(f"{'band':>8} {'samples':>9} {'p50 m':>8} {'p99 m':>8} {'max m':>8}", file=out)
        for b, f in fig["bands"].items():
            print(f"{b:>8} {f['samples']:>9} {f['p50_m']:>8.3f} {f['p99_m']:>8.3f} "
                  f"{f['max_m']:>8.3f}", file=out)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--json"]
    if len(args) != 1:
        sys.exit("usage: truth_error.py [--json] RUN_DIR")
    fig = figures(*join(args[0]))
    print(json.dumps(fig, indent=2) if "--json" in sys.argv else "", end="")
    if "--json" not in sys.argv:
        print_table(fig)
