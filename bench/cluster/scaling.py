#!/usr/bin/env python3
"""Strong and weak scaling of the zone cluster on this machine, with the per-phase tick profile.

Strong: one scene (16,000 walking NPCs and 200 spheres on 400 m x 400 m) on 1, 2 and 4 ranks.
Weak: 4,000 NPCs per rank on 200 m x 200 m per rank (1, 2, 4 ranks).
Each run: 600 ticks as fast as possible, --no-dds (no gateway), conservation checked every
30 ticks. Reported per run: wall ms per tick (tick loop only), speed-up / efficiency, migrations
per tick, and the mean time per phase on the slowest rank. 4 ranks on the 2-core machine are
oversubscribed: read those rows as such.

Usage: bench/cluster/scaling.py [BUILD_DIR]
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
TICKS = 600
PHASES = ["input", "ai", "physics", "gpu", "migrate", "halo", "publish", "checks"]
GRIDS = {1: (1, 1), 2: (2, 1), 4: (2, 2)}


def scene(path, width, depth, npcs, bodies):
    path.write_text(f"""name: scaling
world: {{min: [0, 0, 0], max: [{width}, 40, {depth}]}}
tick: {{dt: 0.0333333333333}}
seed: 3
zones: {{columns: 1, rows: 1}}
populations:
  - {{kind: npc, count: {npcs}, speed: [1.0, 2.5], waypoint_radius: 60}}
  - {{kind: rigid_body, count: {bodies}, drop_height: [2, 10]}}
""")


def run(scene_path, ranks, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "-np", str(ranks), "--oversubscribe", "--bind-to", "none",
                    str(BUILD / "bin/zone_node"), "--scene", str(scene_path), "--ticks", str(TICKS),
                    "--no-dds", "--metrics", str(out)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    zones = [json.loads((out / f"zone_{r}_summary.json").read_text()) for r in range(ranks)]
    assert all(z["conservation_failures"] == 0 for z in zones)
    slowest = max(zones, key=lambda z: sum(z[f"{p}_ms_mean"] for p in PHASES))
    return {
        "ms_per_tick": max(z["wall_s"] for z in zones) * 1e3 / TICKS,
        "migrations_per_tick": sum(z["migrated_out"] for z in zones) / TICKS,
        "entities": sum(z["entities_end"] for z in zones),
        "phases": {p: slowest[f"{p}_ms_mean"] for p in PHASES},
    }


def table(title, rows, base):
    print(f"\n{title}")
    print(f"{'ranks':>5} {'entities':>8} {'ms/tick':>8} {'speed-up':>8} {'eff.':>5} {'migr/tick':>9}  "
          + " ".join(f"{p:>7}" for p in PHASES) + "   (ms, slowest rank)")
    for ranks, r in rows:
        speedup = base / r["ms_per_tick"] if title.startswith("strong") else base / r["ms_per_tick"]
        eff = speedup / ranks if title.startswith("strong") else speedup
        note = " (oversubscribed)" if ranks > 2 else ""
        print(f"{ranks:>5} {r['entities']:>8} {r['ms_per_tick']:>8.3f} {speedup:>8.2f} {eff:>5.2f} "
              f"{r['migrations_per_tick']:>9.1f}  " + " ".join(f"{r['phases'][p]:>7.3f}" for p in PHASES)
              + note)


with tempfile.TemporaryDirectory() as tmp:
    tmp = Path(tmp)
    strong_scene = tmp / "strong.yaml"
    scene(strong_scene, 400, 400, 16000, 200)
    strong = [(n, run(strong_scene, n, tmp / f"s{n}")) for n in (1, 2, 4)]
    table("strong scaling: 16,000 NPCs + 200 spheres, 400 m x 400 m", strong, strong[0][1]["ms_per_tick"])
    weak = []
    for n in (1, 2, 4):
        cols, rows = GRIDS[n]
        path = tmp / f"weak{n}.yaml"
        scene(path, 200 * cols, 200 * rows, 4000 * n, 50 * n)
        weak.append((n, run(path, n, tmp / f"w{n}")))
    table("weak scaling: 4,000 NPCs + 50 spheres per rank on 200 m x 200 m per rank (efficiency = "
          "t1 / tN)", weak, weak[0][1]["ms_per_tick"])
