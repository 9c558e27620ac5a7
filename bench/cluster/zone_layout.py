#!/usr/bin/env python3
"""Zone count and layout against cost and outcome (issue 19's work-precision sweep).

One scene, 8,000 walking NPCs that keep apart (separation through ghosts) and 400 spheres
dropped in piles on 240 m x 240 m, run for 300 ticks on each zone layout: 1x1, 2x1, 1x2, 4x1,
2x2, 1x4 (one rank per zone, --no-dds). Cost: wall ms per tick of the slowest rank, migrations,
ghosts sent and halo bytes per tick. Outcome: every entity's end state against the 1x1 run:
the walkers should end bitwise where one zone ends them (decomposition invariance); bodies whose
contacts cross a zone border are solved by each zone with pushed ghosts and move off (the
cross-zone error, docs/physics.md). 4 ranks on a 2-core machine are oversubscribed: their
times are read as such; the counts and the outcome are not affected.

Usage: bench/cluster/zone_layout.py [BUILD_DIR] [--plot PNG]
The plot (bench/sweep_figure.py): per layout, the border traffic with the entities that end
elsewhere than on one zone, and the wall time per tick.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ARGS = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ARGS.add_argument("build", nargs="?", default=str(ROOT / "build"))
ARGS.add_argument("--plot", help="write the work-precision plot here (PNG)")
OPTS = ARGS.parse_args()
BUILD = Path(OPTS.build)
TICKS = 300
LAYOUTS = [(1, 1), (2, 1), (1, 2), (4, 1), (2, 2), (1, 4)]


def scene(path, columns, rows):
    path.write_text(f"""name: zone_layout
world: {{min: [0, 0, 0], max: [240, 40, 240]}}
tick: {{dt: 0.05}}
seed: 5
zones: {{columns: {columns}, rows: {rows}}}
interest: {{cell_size: 30}}
halo: {{width: 3}}
populations:
  - kind: npc
    count: 8000
    speed: [1.0, 2.0]
    acceleration: 3
    waypoint_radius: 40
    separation: {{radius: 2.0, weight: 1.5}}
  - kind: rigid_body
    count: 400
    drop_height: [1, 12]
    region: {{min: [100, 0, 100], max: [140, 0, 140]}}
""")


def run(scene_path, ranks, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    dump = out / "state.jsonl"
    subprocess.run(["mpirun", "-np", str(ranks), "--oversubscribe", "--bind-to", "none",
                    str(BUILD / "bin/zone_node"), "--scene", str(scene_path), "--ticks", str(TICKS),
                    "--no-dds", "--metrics", str(out), "--dump-state", str(dump)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    zones = [json.loads((out / f"zone_{r}_summary.json").read_text()) for r in range(ranks)]
    assert all(z["conservation_failures"] == 0 for z in zones)
    states = {}
    for line in dump.read_text().splitlines():
        e = json.loads(line)
        states[e["id"]] = e
    return {
        "ms_per_tick": max(z["wall_s"] for z in zones) * 1e3 / TICKS,
        "migrations": sum(z["migrated_out"] for z in zones) / TICKS,
        "ghosts": sum(z["ghosts_sent"] for z in zones) / TICKS,
        "halo_kib": sum(z["halo_bytes"] for z in zones) / TICKS / 1024,
        "states": states,
    }


def drift(base, other, kind):
    """Mean and max end-position distance of `kind` entities from the 1x1 run, and how many
    differ at all."""
    d = []
    for i, e in base["states"].items():
        if e["kind"] != kind:
            continue
        o = other["states"][i]
        d.append(math.dist(e["pos"], o["pos"]))
    moved = sum(1 for x in d if x > 0)
    return (sum(d) / len(d) if d else 0.0), (max(d) if d else 0.0), moved, len(d)


def plot(results, base, path):
    sys.path.insert(0, str(ROOT / "bench"))
    from sweep_figure import plt, save
    fig, (border, cost) = plt.subplots(1, 2, figsize=(10, 4.2))
    names = [f"{c}x{r}" for c, r in results]
    xs = range(len(names))
    kib = [r["halo_kib"] for r in results.values()]
    border.bar(xs, kib, color="tab:blue", label="halo KiB / tick")
    border.set_ylabel("halo KiB per tick (sum over the zones)")
    mig = border.twinx()
    mig.plot(xs, [r["migrations"] for r in results.values()], "o", color="tab:red")
    mig.set_ylabel("migrations per tick", color="tab:red")
    for i, r in enumerate(results.values()):  # the precision: what ends elsewhere than on 1x1
        body_mean, _, bodies, _ = drift(base, r, "rigid_body")
        walkers = drift(base, r, "npc")[2]
        label = f"moved:\n{walkers} w, {bodies} b"
        if body_mean > 0:
            label += f"\n{body_mean:.2f} m"
        border.annotate(label, (i, kib[i]), ha="center", fontsize=7, textcoords="offset points",
                        xytext=(0, 2))
    border.set_ylim(0, max(kib) * 1.3)
    border.set_title("border traffic, and entities whose end state differs from 1x1\n(w: of "
                     f"{sum(1 for e in base['states'].values() if e['kind'] == 'npc')} walkers, "
                     f"b: of {sum(1 for e in base['states'].values() if e['kind'] == 'rigid_body')} "
                     "bodies)", fontsize=9)
    ms = [r["ms_per_tick"] for r in results.values()]
    cost.bar(xs, ms, color=["tab:gray" if c * r > 2 else "tab:green" for c, r in results])
    cost.set_ylim(0, max(ms) * 1.2)
    cost.set_ylabel("wall ms per tick, slowest rank")
    cost.set_title("tick time (grey: 4 ranks on 2 shared cores, oversubscribed)", fontsize=9)
    for ax in (border, cost):
        ax.set_xticks(list(xs), names)
        ax.set_xlabel("zone layout (columns x rows), one rank per zone")
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle(f"zone count and layout: 8,000 walkers + 400 spheres, {TICKS} ticks", fontsize=10)
    save(fig, path)


with tempfile.TemporaryDirectory() as tmp:
    tmp = Path(tmp)
    results = {}
    for cols, rows in LAYOUTS:
        path = tmp / f"l{cols}x{rows}.yaml"
        scene(path, cols, rows)
        out = tmp / f"o{cols}x{rows}"
        out.mkdir()
        print(f"  running {cols}x{rows} ...", file=sys.stderr, flush=True)
        results[(cols, rows)] = run(path, cols * rows, out)
    base = results[(1, 1)]
    print(f"zone layout: 8,000 separating walkers + 400 spheres on 240 m x 240 m, {TICKS} ticks")
    print("| layout | ranks | ms/tick | migrations/tick | ghosts sent/tick | halo KiB/tick | "
          "walkers moved | bodies moved | body drift mean m | max m |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (cols, rows), r in results.items():
        _, _, npc_moved, npcs = drift(base, r, "npc")
        body_mean, body_max, body_moved, bodies = drift(base, r, "rigid_body")
        note = " (oversubscribed)" if cols * rows > 2 else ""
        print(f"| {cols}x{rows} | {cols * rows} | {r['ms_per_tick']:.3f}{note} | "
              f"{r['migrations']:.2f} | {r['ghosts']:.1f} | {r['halo_kib']:.2f} | "
              f"{npc_moved} of {npcs} | {body_moved} of {bodies} | {body_mean:.4f} | "
              f"{body_max:.4f} |")
    if OPTS.plot:
        plot(results, base, OPTS.plot)
