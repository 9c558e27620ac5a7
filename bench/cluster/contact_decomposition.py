#!/usr/bin/env python3
"""How a contact scene differs across decompositions (issue 5: "for contact scenes state what
differs and by how much").

scenes/border_pile.yaml drops 400 spheres (r = 0.5 m) onto the point where four zones meet and
runs 600 ticks at 60 Hz on 1, 2 and 4 ranks (--no-dds). Every island of bodies that may touch is
stepped whole by the rank holding its lowest id (zone_node/systems/body_islands.h), so the pile
should end bitwise where it ends on 1 rank. Reported: distance of each sphere from where it ends
on 1 rank (median, p90, max), the deepest overlap of any two spheres at the end (all pairs, so
also pairs of different zones), the bodies solved in another zone's islands, and the mean
physics + halo time per tick on the slowest rank.

Usage: bench/cluster/contact_decomposition.py [BUILD_DIR]
"""
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
SCENE = ROOT / "scenes/border_pile.yaml"
RADIUS = 0.5


def run(ranks, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    dump, metrics = out / f"state_{ranks}.jsonl", out / f"metrics_{ranks}"
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), str(BUILD / "bin/zone_node"),
                    "--scene", str(SCENE), "--ticks", "600", "--no-dds", "--dump-state",
                    str(dump), "--metrics", str(metrics)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    state = {d["id"]: d["pos"] for d in map(json.loads, dump.open())}
    summaries = [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]
    return state, summaries


def deepest_overlap(positions):
    worst = 0.0
    for i in range(len(positions)):
        for j in range(i + 1, len(positions)):
            worst = max(worst, 2 * RADIUS - math.dist(positions[i], positions[j]))
    return worst


def main():
    with tempfile.TemporaryDirectory(prefix="zs_contact_") as tmp:
        runs = {}
        for ranks in (1, 2, 4):
            print(f"running {ranks} rank(s)...", file=sys.stderr, flush=True)
            runs[ranks] = run(ranks, Path(tmp))
    reference = runs[1][0]
    print("| ranks | median / p90 / max distance from the 1-rank end (m) | deepest overlap (mm) "
          "| bodies solved in other zones' islands | physics + halo ms/tick (slowest rank) |")
    print("|---|---|---|---|---|")
    for ranks, (state, summaries) in runs.items():
        d = sorted(math.dist(reference[k], state[k]) for k in reference)
        spread = f"{d[len(d) // 2]:.3f} / {d[int(0.9 * len(d))]:.3f} / {d[-1]:.3f}"
        pushes = sum(s.get("island_bodies_out", 0) for s in summaries)
        cost = max(s["physics_ms_mean"] + s.get("halo_ms_mean", 0) for s in summaries)
        print(f"| {ranks}{' (oversubscribed)' if ranks == 4 else ''} | {spread} | "
              f"{1e3 * max(0.0, deepest_overlap(list(state.values()))):.1f} | {pushes} | {cost:.2f} |")


if __name__ == "__main__":
    main()
