#!/usr/bin/env python3
"""Time per zone tick for a large flock with --gpu off (the crowd library's double flock) and
--gpu on (gpu::PlanarFlock on OpenCL; PoCL here), in one run.

Scenes: scenes/flock_large.yaml's flock (0.3 agents per m^2, radius 3 m) at 20,000 and
100,000 agents, the world grown to keep the density, 2x2 zones on RANKS ranks (default 2).
Each run: TICKS ticks (default 40) as fast as possible, --no-dds. The modes alternate, REPEATS
times (default 3), so both see the same machine load; reported per mode: the median over the
repeats of the slowest rank's median tick and median time in the ai phase (where flocks step),
the first 2 ticks left out, and the off/on ratios.

Usage: bench/gpu/zone_flock_bench.py [BUILD_DIR] [--ranks N] [--ticks N] [--repeats N]
                                     [--sizes 20000,100000]
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DENSITY = 0.3  # agents per m^2, as scenes/flock_large.yaml
WARMUP = 2  # first ticks left out: PoCL compiles a kernel for its work-group size at first launch


def scene(path, agents):
    side = round(math.sqrt(agents / DENSITY), 1)
    path.write_text(f"""name: zone_flock_bench
world: {{min: [0, 0, 0], max: [{side}, 20, {side}]}}
tick: {{dt: 0.05}}
seed: 23
zones: {{columns: 2, rows: 2}}
interest: {{cell_size: {side / 8:.1f}}}
halo: {{width: 3}}
populations:
  - kind: npc
    count: {agents}
    speed: [1.5, 2.0]
    flock: {{radius: 3.0, separation: {{radius: 1.0, weight: 20}}, alignment: 1.0,
             cohesion: 0.5, max_speed: 2.0, max_force: 8.0}}
""")


def run(build, scene_path, mode, ranks, ticks, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "-np", str(ranks), "--oversubscribe", "--bind-to", "none",
                    str(build / "bin/zone_node"), "--scene", str(scene_path), "--ticks",
                    str(ticks), "--no-dds", "--gpu", mode, "--metrics", str(out)],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    zones = [json.loads((out / f"zone_{r}_summary.json").read_text()) for r in range(ranks)]
    want = "opencl" if mode == "on" else "cpu"
    assert all(z["flock_backend"] == want for z in zones), [z["flock_backend"] for z in zones]
    tick, ai = [], []
    for r in range(ranks):
        rows = [json.loads(line) for line in (out / f"zone_{r}.jsonl").read_text().splitlines()]
        rows = rows[WARMUP:]
        tick.append(statistics.median(row["tick_ms"] for row in rows))
        ai.append(statistics.median(row["ai_ms"] for row in rows))
    return max(tick), max(ai)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("build", nargs="?", default=str(ROOT / "build"))
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--ticks", type=int, default=40)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--sizes", default="20000,100000")
    a = p.parse_args()
    build = Path(a.build)
    print(f"{a.ranks} ranks, {a.ticks} ticks, median of {a.repeats} alternating runs; "
          "ms, slowest rank")
    print(f"{'agents':>8} {'off tick':>12} {'on tick':>12} {'off/on':>7} "
          f"{'off ai':>8} {'on ai':>8} {'off/on':>7}")  # medians per tick
    with tempfile.TemporaryDirectory(prefix="zs_flock_bench_") as tmp:
        tmp = Path(tmp)
        for agents in (int(s) for s in a.sizes.split(",")):
            path = tmp / f"flock_{agents}.yaml"
            scene(path, agents)
            got = {"off": [], "on": []}
            for r in range(a.repeats):
                for mode in ("off", "on"):
                    got[mode].append(run(build, path, mode, a.ranks, a.ticks,
                                         tmp / f"m_{agents}_{mode}_{r}"))
            med = {m: (statistics.median(t for t, _ in v), statistics.median(ai for _, ai in v))
                   for m, v in got.items()}
            print(f"{agents:>8} {med['off'][0]:>12.1f} {med['on'][0]:>12.1f} "
                  f"{med['off'][0] / med['on'][0]:>7.2f} {med['off'][1]:>8.1f} "
                  f"{med['on'][1]:>8.1f} {med['off'][1] / med['on'][1]:>7.2f}")


if __name__ == "__main__":
    main()
