#!/usr/bin/env python3
"""The player's own stream around handoffs, from client_stub's own_stream.csv (issue 6).

Each client logs when a new state of its own avatar arrives ("U": sample tick, receive time,
its estimate of the server tick) and when a Handoff notice arrives ("H": the crossing tick).
Per handoff with crossing tick T:
  - gap: receive time of the first own state sampled at or after T (the new owner's) minus that
    of the last one sampled before T: how long the player heard nothing of its avatar across
    the move;
  - first: the new owner's first state, its sample tick - T, and its receive lag (the player's
    server-tick estimate at receipt - its sample tick).
The "normal" stream for comparison, from the same run: gaps between consecutive own states,
and the gap spanning a control instant (each whole second of a player's run at least 1 s from
any of its handoffs), which like a handoff falls in a gap with probability by its length.
Dead reckoning makes the own stream irregular (a walker in a straight line is heard of at the
heartbeat; one turning, every tick), so the comparison is the distribution, not one interval.

Usage: deploy/own_stream.py RUN_DIR/own_stream.csv   (prints the table)
"""
import bisect
import csv
import sys
from collections import defaultdict


def pct(v, p):
    v = sorted(v)
    return v[min(len(v) - 1, max(0, int(round(p / 100 * len(v) + 0.5)) - 1))] if v else 0.0


def load(path):
    players = defaultdict(lambda: {"U": [], "H": []})
    with open(path) as f:
        for r in csv.DictReader(f):
            players[int(r["player"])][r["event"]].append(
                (float(r["t_ms"]), int(r["tick"]), float(r["server_tick"])))
    return players


def analyse(players):
    out = {k: [] for k in ("gap_ms", "normal_gap_ms", "control_gap_ms", "first_offset_ticks",
                           "first_lag_ticks", "lag_ticks")}
    out["handoffs"] = out["unmatched"] = 0
    for p in players.values():
        own = sorted(p["U"])  # by receive time
        times = [u[0] for u in own]
        out["normal_gap_ms"] += [b - a for a, b in zip(times, times[1:])]
        out["lag_ticks"] += [u[2] - u[1] for u in own]
        for t_h, T, _ in p["H"]:
            out["handoffs"] += 1
            before = [u for u in own if u[1] < T]
            after = [u for u in own if u[1] >= T]
            if not before or not after:
                out["unmatched"] += 1  # the player joined or left right at the crossing
                continue
            first = min(after, key=lambda u: u[0])
            out["gap_ms"].append(first[0] - max(u[0] for u in before))
            out["first_offset_ticks"].append(first[1] - T)
            out["first_lag_ticks"].append(first[2] - first[1])
        hand = sorted(h[0] for h in p["H"])
        if len(times) < 2:
            continue
        for s in range(int(times[0] / 1000) + 1, int(times[-1] / 1000)):
            t = s * 1000.0
            k = bisect.bisect_left(hand, t)
            near = [hand[j] for j in (k - 1, k) if 0 <= j < len(hand)]
            if any(abs(t - h) < 1000 for h in near):
                continue
            i = bisect.bisect_right(times, t)
            out["control_gap_ms"].append(times[i] - times[i - 1])
    return out


def rows(a):
    """(label, samples, unit) rows of the table."""
    return [
        ("own states: gap between receipts", a["normal_gap_ms"], "ms"),
        ("own states: gap spanning a control instant", a["control_gap_ms"], "ms"),
        ("handoff: gap spanning the crossing", a["gap_ms"], "ms"),
        ("handoff: new owner's first state, sample tick - T", a["first_offset_ticks"], "ticks"),
        ("handoff: receive lag of that state", a["first_lag_ticks"], "ticks"),
        ("own states: receive lag", a["lag_ticks"], "ticks"),
    ]


def summary(a):
    return {label: {"n": len(v), "p50": pct(v, 50), "p99": pct(v, 99), "max": max(v) if v else 0}
            for label, v, _ in rows(a)} | {"handoffs": a["handoffs"], "unmatched": a["unmatched"]}


def print_table(a, out=sys.stdout):
    print(f"own stream around {a['handoffs']} handoffs ({a['unmatched']} at a join or leave)",
          file=out)
    print(f"{'':58} {'n':>7} {'p50':>8} {'p99':>8} {'max':>8}", file=out)
    for label, v, unit in rows(a):
        if v:
            print(f"{label + ' (' + unit + ')':58} {len(v):>7} {pct(v, 50):>8.1f} {pct(v, 99):>8.1f} "
                  f"{max(v):>8.1f}", file=out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: own_stream.py OWN_STREAM.csv")
    print_table(analyse(load(sys.argv[1])))
