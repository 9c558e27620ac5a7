#!/usr/bin/env python3
"""Load balancing on scenes/hotspot.yaml (a crowd that stays in one corner) or, with
`--gather`, scenes/hotspot_gather.yaml (a crowd that converges on one point from 5 s to 25 s,
then disperses; 1,500 ticks): 4 zone ranks with fixed boundaries and with --balance-every,
as fast as possible. Prints per-rank own-work time per tick
(input + ai + physics + gpu + publish: the part a rank controls) and max/mean over three
windows, entities per zone, and the final rectangles.

Usage: bench/cluster/hotspot_balance.py [--gather] [BUILD_DIR] [BALANCE_EVERY]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GATHER = "--gather" in sys.argv
ARGS = [a for a in sys.argv[1:] if a != "--gather"]
BUILD = Path(ARGS[0]) if len(ARGS) > 0 else ROOT / "build"
EVERY = int(ARGS[1]) if len(ARGS) > 1 else 30
SCENE = ROOT / ("scenes/hotspot_gather.yaml" if GATHER else "scenes/hotspot.yaml")
TICKS = 1500 if GATHER else 600
# Gather: spread out, converging (5-20 s), gathered (20-25 s), dispersing (25-50 s).
WINDOWS = ([(0, 150), (150, 600), (600, 750), (750, 1500)] if GATHER
           else [(0, 100), (100, 300), (300, 600)])


def own_ms(line):
    return sum(line[k] for k in ("input_ms", "ai_ms", "physics_ms", "gpu_ms", "publish_ms"))


def run(every, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "-np", "4", "--oversubscribe", str(BUILD / "bin/zone_node"), "--scene",
                    str(SCENE), "--ticks", str(TICKS), "--no-dds",
                    "--balance-every", str(every), "--metrics", str(out)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    zones = [json.loads((out / f"zone_{r}_summary.json").read_text()) for r in range(4)]
    ticks = [[json.loads(l) for l in (out / f"zone_{r}.jsonl").read_text().splitlines()] for r in range(4)]
    print(f"\n--balance-every {every}: rebalances {sum(z['rebalances'] for z in zones)}, "
          f"migrations {sum(z['migrated_out'] for z in zones)}, "
          f"conservation failures {sum(z['conservation_failures'] for z in zones)}")
    print(f"  entities per zone: start {[z['entities_start'] for z in zones]} end {[z['entities_end'] for z in zones]}")
    for lo, hi in WINDOWS:
        per_rank = [sum(own_ms(l) for l in ticks[r][lo:hi]) / (hi - lo) for r in range(4)]
        print(f"  ticks {lo:>4}-{hi:<4} own-work ms/tick per rank {[round(x, 3) for x in per_rank]}  "
              f"max {max(per_rank):.3f}  max/mean {max(per_rank) / statistics.mean(per_rank):.2f}")
    print(f"  final rects (min_x, min_z, max_x, max_z): {[[round(v, 1) for v in z['rect']] for z in zones]}")


with tempfile.TemporaryDirectory() as tmp:
    if GATHER:
        print("hotspot_gather: 5,000 NPCs converge on (40, 40) from 5 s to 25 s, then disperse; "
              "4 ranks (oversubscribed on 2 cores), 1,500 ticks")
    else:
        print("hotspot: 6,000 NPCs in a 120 m corner + 400 spread over 400 m x 400 m, 4 ranks "
              "(oversubscribed on 2 cores), 600 ticks")
    run(0, Path(tmp) / "fixed")
    run(EVERY, Path(tmp) / "balanced")
