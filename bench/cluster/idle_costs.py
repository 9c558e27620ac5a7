#!/usr/bin/env python3
"""What each zone system costs per tick when it has nothing to do (issue 19).

One zone_node rank runs, unpaced, small scenes in which a system is absent (the scene has
none of its kind), empty, asleep or unsubscribed, and this prints each tick stage's mean cost
(µs per tick, from --metrics' zone_0_summary.json) beside the work counters that say the
system did nothing. A stage's cost includes its timer (two clock reads, about 40 ns).

Means are over the per-tick lines (zone_0.jsonl) of the measured ticks: all TICKS for most
cases; for sleeping bodies the TICKS after SETTLE, by which every body sleeps (checked), so that
settling does not count, and likewise for the courtyard's flow crowd (scenes/courtyard_flow.yaml,
every NPC arrived by 38.7 s, tick 774: checked by its visits). Counters are summed over the
same ticks.

Usage: bench/cluster/idle_costs.py [TICKS]   (default 4000; ZONESIM_BIN=build/bin)
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
TICKS = int(sys.argv[1]) if len(sys.argv) > 1 else 4000
SETTLE = 1500

BASE = """world: {min: [0, 0, 0], max: [200, 50, 200]}
tick: {dt: 0.05}
seed: 7
zones: {columns: 1, rows: 1}
interest: {cell_size: 25}
"""
SCENES = {
    # Nothing at all: the floor every stage sits on.
    "empty world": BASE,
    # Walkers only: physics, particles, AI planners, crowds and agents are absent.
    "walkers only": BASE + """populations:
  - {kind: npc, count: 500, speed: [1.0, 2.0], waypoint_radius: 40}
""",
    # Bodies that settle and sleep (measured after they all sleep, see above).
    "bodies asleep": BASE + """physics: {sleep: true}
populations:
  - {kind: rigid_body, count: 200, shape: box, size: [1, 1, 1], drop_height: [0.6, 0.6],
     region: {min: [20, 0, 20], max: [180, 0, 180]}}
""",
}
# A flow crowd whose NPCs have all arrived (the shipped scene: it names its map file).
ARRIVED_CROWD = ROOT / "scenes" / "courtyard_flow.yaml"
STAGES = ("input", "ai.doors", "ai.neighbours", "ai.lod", "ai.interactions", "ai.agents",
          "ai.wander", "ai.flock", "ai.flow", "ai.formations", "ai.roads", "ai.ants", "avatars",
          "physics", "gpu", "migrate", "halo", "publish", "checks")
COUNTERS = ("physics_steps", "bodies_checked", "bodies_awake", "particles_alive", "paths_planned", "agents",
            "flow_npcs_visited", "ghosts", "published_states", "published_updates")


def run(scene_text, ticks, tmp, tag, dds=False, scene_file=None):
    """Per-tick metric lines of one zone_node run (of scene_text, or of a shipped scene_file)."""
    scene = scene_file or Path(tmp) / f"{tag}.yaml"
    if scene_file is None:
        scene.write_text(scene_text)
    metrics = Path(tmp) / f"m_{tag}_{ticks}"
    cmd = [str(BIN / "zone_node"), "--scene", str(scene), "--ticks", str(ticks), "--metrics",
           str(metrics), "--gpu", "off", "--log-level", "warn"]
    env = dict(os.environ)
    if dds:
        env["CYCLONEDDS_URI"] = "file://" + str(ROOT / "deploy" / "cyclonedds.xml")
        cmd += ["--dds-domain", "37"]
    else:
        cmd.append("--no-dds")
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    return [json.loads(line) for line in (metrics / "zone_0.jsonl").read_text().splitlines()]


def measured(lines, first_tick):
    """Mean µs per tick of each stage and summed counters over ticks >= first_tick."""
    rows = [r for r in lines if r["tick"] >= first_tick]
    costs = {s: 1000.0 * sum(r.get(f"{s}_ms", 0.0) for r in rows) / len(rows) for s in STAGES}
    counters = {c: sum(r.get(c, 0) for r in rows) for c in COUNTERS}
    return costs, counters


def main():
    rows = []
    with tempfile.TemporaryDirectory(prefix="zs_idle_") as tmp:
        for name, text in SCENES.items():
            asleep = name == "bodies asleep"
            lines = run(text, SETTLE + TICKS if asleep else TICKS, tmp, name.replace(" ", "_"))
            first = SETTLE + 1 if asleep else 1
            if asleep and any(r["bodies_awake"] for r in lines if r["tick"] >= first):
                sys.exit(f"bodies asleep: some still awake after tick {SETTLE}")
            costs, counters = measured(lines, first)
            rows.append((name, costs, counters))
            print(f"  {name}: done", file=sys.stderr, flush=True)
        # A flow crowd asleep: every NPC arrived (measured after SETTLE, like the bodies).
        lines = run(None, SETTLE + TICKS, tmp, "arrived_crowd", scene_file=ARRIVED_CROWD)
        if any(r["flow_npcs_visited"] for r in lines if r["tick"] > SETTLE):
            sys.exit(f"flow crowd: NPCs still on the way after tick {SETTLE}")
        rows.append(("flow crowd, all arrived", *measured(lines, SETTLE + 1)))
        print("  flow crowd, all arrived: done", file=sys.stderr, flush=True)
        # Cells nobody subscribes to: the walkers published over DDS with no gateway attached.
        lines = run(SCENES["walkers only"], TICKS, tmp, "unsubscribed", dds=True)
        rows.append(("walkers, DDS, no subscriber", *measured(lines, 1)))
    print(f"µs per tick (mean over {TICKS} ticks, one zone, unpaced); counters summed over them")
    print("| stage | " + " | ".join(name for name, _, _ in rows) + " |")
    print("| --- " * (1 + len(rows)) + "|")
    for st in STAGES:
        print(f"| {st} | " + " | ".join(f"{costs[st]:.2f}" for _, costs, _ in rows) + " |")
    for c in COUNTERS:
        print(f"| *{c}* | " + " | ".join(str(n[c]) for _, _, n in rows) + " |")


if __name__ == "__main__":
    main()
