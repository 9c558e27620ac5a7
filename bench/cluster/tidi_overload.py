#!/usr/bin/env python3
"""Time dilation under overload (issue 15): scenes/test_overload.yaml (3,000 walkers packed
into 6 m in zone 0, about ten 30 Hz budgets a tick until they spread out after a few seconds)
on 2 ranks in real time, with --time-dilation on and off. Prints, per wall-clock second of rank 0, the ticks run, their tick
time p50/p99, the sim speed (sim seconds per wall second) and the ticks that ended after their
deadline (late: the loop then runs the next ticks back to back to catch up, which is what
missing ticks looks like to a player); then the run's totals.

Usage: bench/cluster/tidi_overload.py [BUILD_DIR] [TICKS]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
TICKS = int(sys.argv[2]) if len(sys.argv) > 2 else 900
SCENE = ROOT / "scenes/test_overload.yaml"
DT = 1 / 30  # the scene's tick


def pct(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, int(round(p / 100 * (len(v) - 1))))] if v else 0.0


def run(mode, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "-np", "2", "--oversubscribe", "--bind-to", "none",
                    str(BUILD / "bin/zone_node"), "--scene", str(SCENE), "--ticks", str(TICKS),
                    "--no-dds", "--realtime", "--time-dilation", mode, "--metrics", str(out)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = [json.loads(l) for l in (out / "zone_0.jsonl").read_text().splitlines()]
    summary = json.loads((out / "zone_0_summary.json").read_text())
    print(f"\n--time-dilation {mode}")
    print("  wall s  ticks  tick ms p50    p99  sim speed  factor  late")
    by_second = {}
    for r in rows:
        by_second.setdefault(int(r["wall_s"]), []).append(r)
    for second, rs in sorted(by_second.items()):
        ms = [r["tick_ms"] for r in rs]
        print(f"  {second:>6}  {len(rs):>5}  {pct(ms, 50):>11.2f} {pct(ms, 99):>6.2f}"
              f"  {len(rs) * DT:>9.2f}  {min(r['dilation'] for r in rs):>6.2f}"
              f"  {sum(r['late'] for r in rs):>4}")
    wall = summary["wall_s"]
    print(f"  total: {summary['ticks']} ticks in {wall:.1f} wall s, sim speed "
          f"{summary['ticks'] * DT / wall:.2f}, tick ms p50 {summary['tick_ms_p50']:.2f} "
          f"p99 {summary['tick_ms_p99']:.2f} max {summary['tick_ms_max']:.2f}, late ticks "
          f"{summary['late_ticks']}, lowest factor {summary['dilation_min']:.2f}, "
          f"{summary['dilation_changes']} steps, {summary['dilated_ticks']} dilated ticks over "
          f"{summary['dilated_wall_s']:.1f} wall s")


with tempfile.TemporaryDirectory() as tmp:
    print(f"test_overload: 3,000 packed walkers in zone 0 of 2, 30 Hz, {TICKS} ticks, real time")
    for mode in ("off", "on"):
        run(mode, Path(tmp) / mode)
