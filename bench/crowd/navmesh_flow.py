#!/usr/bin/env python3
"""The courtyard's flow crowd on the grid field and on the navigation mesh (issue 18).

Runs scenes/courtyard_flow.yaml (aims at the next cell's centre of the grid field's octile path)
and scenes/courtyard_flow_navmesh.yaml (aims at the first corner of the funnelled mesh path,
crowd/flow_waypoints.h) on one zone_node rank, unpaced, for TICKS ticks of 0.05 s, and prints
how many of the 400 NPCs arrived, their mean, median and last arrival time (zone_node
--arrivals), and the flow stage's mean time per tick (--metrics; the crowd sleeps once all have
arrived, so this is a mean over the run, not per walking NPC).

Usage: bench/crowd/navmesh_flow.py [TICKS]   (default 1200; ZONESIM_BIN=build/bin)
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
TICKS = int(sys.argv[1]) if len(sys.argv) > 1 else 1200
DT = 0.05  # the courtyard's tick

print(f"courtyard flow crowd, 400 NPCs, {TICKS} ticks, one rank")
print("| scene | arrived | mean s | median s | last s | ai.flow ms/tick |")
print("|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory(prefix="zs_navflow_") as tmp:
    for scene in ("courtyard_flow", "courtyard_flow_navmesh"):
        arrivals, metrics = Path(tmp) / f"{scene}.csv", Path(tmp) / scene
        subprocess.run([str(BIN / "zone_node"), "--scene", str(ROOT / "scenes" / f"{scene}.yaml"),
                        "--ticks", str(TICKS), "--no-dds", "--gpu", "off", "--log-level", "warn",
                        "--arrivals", str(arrivals), "--metrics", str(metrics)],
                       check=True, stdout=subprocess.DEVNULL)
        ticks = sorted(int(line.split(",")[1]) for line in arrivals.read_text().split()[1:])
        flow_ms = json.loads((metrics / "zone_0_summary.json").read_text())["ai.flow_ms_mean"]
        seconds = [t * DT for t in ticks]
        print(f"| {scene} | {len(ticks)} | {sum(seconds) / len(seconds):.2f} | "
              f"{seconds[len(seconds) // 2]:.2f} | {seconds[-1]:.2f} | {flow_ms:.4f} |")
