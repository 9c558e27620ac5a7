#!/usr/bin/env python3
"""Handoff latency and input loss over many handoffs (issue 6).

Runs deploy/demo.sh on scenes/handoff_stress.yaml (4 zone ranks, one gateway, PLAYERS players,
SECONDS s, real time at 30 Hz) and reads the zones' summaries. Handoff latency is measured by
the new owner: ticks from the avatar's arrival (the tick it crossed the border) to the first
input it applies, times the tick period. Also reported: inputs applied, duplicates discarded
(already applied), inputs forwarded by an old owner, sequence numbers skipped (never arrived),
the player's own stream around each handoff against the same stream elsewhere
(deploy/own_stream.py: the clients' logs of their avatar's states), and histograms of both.

Usage: /usr/bin/python3 bench/net/handoff_bench.py [PLAYERS] [SECONDS] [PLOT.png]
(the plot needs matplotlib: python3-matplotlib, hence the system interpreter)
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "deploy"))
import own_stream  # noqa: E402
PLAYERS = int(sys.argv[1]) if len(sys.argv) > 1 else 128
SECONDS = int(sys.argv[2]) if len(sys.argv) > 2 else 60
PLOT = Path(sys.argv[3]) if len(sys.argv) > 3 else None


def pct(v, p):
    v = sorted(v)
    return v[min(len(v) - 1, max(0, int(round(p / 100 * len(v) + 0.5)) - 1))] if v else 0.0


with tempfile.TemporaryDirectory(prefix="zs_handoff_") as tmp:
    env = dict(os.environ, ZONESIM_DEMO_SCENE=str(ROOT / "scenes/handoff_stress.yaml"),
               ZONESIM_DEMO_PLAYERS=str(PLAYERS), ZONESIM_DEMO_SECONDS=str(SECONDS),
               ZONESIM_DEMO_TRUTH_EVERY="0")  # 128 players' display logs: not needed here
    subprocess.run(["bash", str(ROOT / "deploy/demo.sh"), tmp], check=True, env=env,
                   stdout=sys.stderr)
    zones = [json.loads(p.read_text()) for p in sorted(Path(tmp).glob("zone_*_summary.json"))]
    clients = json.loads((Path(tmp) / "clients_summary.json").read_text())
    gaps = own_stream.analyse(own_stream.load(Path(tmp) / "own_stream.csv"))

lat = [ms for z in zones for ms in z.get("handoff_latency_ms", [])]
total = lambda k: sum(z.get(k, 0) for z in zones)
print(f"{PLAYERS} players, {SECONDS} s, 4 zone ranks (oversubscribed on 2 cores)")
told = sum(c.get("handoffs", 0) for c in clients.get("clients", []))
print(f"handoffs: {total('handoffs_in')} (timed {len(lat)}); clients told of {told}")
print(f"latency ms: p50 {pct(lat, 50):.1f}  p90 {pct(lat, 90):.1f}  p99 {pct(lat, 99):.1f}  "
      f"max {max(lat) if lat else 0:.1f}")
print(f"inputs: applied {total('inputs_applied')}, duplicates discarded {total('inputs_duplicate')}, "
      f"forwarded {total('inputs_forwarded')}, held to keep order {total('inputs_held')}, skipped (never arrived) {total('inputs_skipped')}, "
      f"unroutable {total('inputs_unroutable')}")
print()
own_stream.print_table(gaps)
if PLOT and lat:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 3.8))
    tick_ms = 1000 / 30
    edges = [(k - 0.5) * tick_ms for k in range(0, int(max(lat) / tick_ms) + 3)]
    ax.hist(lat, bins=edges, color="#4477aa", rwidth=0.8)  # one bar per whole tick
    ax.set_xlabel("border crossing to first input applied by the new owner (ms)")
    ax.set_ylabel("handoffs")
    ax.set_title(f"latency: {len(lat)} handoffs, {PLAYERS} players, 30 Hz")
    top = max(gaps["gap_ms"] + gaps["control_gap_ms"] + [tick_ms])
    bins = [k * 100 for k in range(int(top / 100) + 2)]
    bx.hist(gaps["control_gap_ms"], bins=bins, density=True, histtype="step", color="#999999",
            label=f"spanning a control instant ({len(gaps['control_gap_ms'])})")
    bx.hist(gaps["gap_ms"], bins=bins, density=True, histtype="step", color="#cc3311",
            label=f"spanning a handoff ({len(gaps['gap_ms'])})")
    bx.set_xlabel("gap in the player's own avatar states (ms)")
    bx.set_ylabel("density")
    bx.set_title("own stream: gap around a handoff vs elsewhere")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(PLOT, dpi=120)
    print(f"plot: {PLOT}")
