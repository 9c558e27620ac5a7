#!/usr/bin/env python3
"""What the scenes' contact solver costs in the shipped scenes (issue 17: the wide soft step is
the default for scenes that name no solver).

Each scene with rigid bodies runs on one rank for TICKS ticks under each solver, as the tuner
runs a scene (bench/tuning/measure.py run_zones: --no-dds, no players), set by an overlay
(overlay_of the shipped scene, physics.solver changed); the solvers alternate, REPEATS rounds,
and the median of each is reported: the zone's physics time per tick
(`physics_ms_mean` of its --metrics summary) and the solve stage's share of it
(`physics.solve_ms_mean`), and the ratio of each to the default's. The scenes that name their
solver (physics_objects, stacks) are not in the default list.

Usage: bench/physics/scene_solvers.py [BUILD_DIR] [--ticks N] [--repeats N] [--scenes a,b]
"""
import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from tuning import knobs, measure  # noqa: E402  (the tuner's overlay and zone runs)

SOLVERS = ("soft_step_wide", "soft_step", "gauss_seidel")  # the default first
SCENES = ("demo", "border_pile", "world_eighth", "compounds", "set_pieces", "duel_arena_16")


def run(build, scene, solver, ticks, work):
    """(physics, solve) ms per tick of one zone-only run of the scene under `solver`."""
    base = ROOT / "scenes" / f"{scene}.yaml"
    overlay = work / f"{scene}.{solver}.yaml"
    overlay.write_text(knobs.overlay_text(base, {"physics.solver": solver}, []))
    folder = work / f"{scene}.{solver}"
    dt = measure.tick_seconds(knobs.merged_scene(base))
    try:
        figures = measure.run_zones(overlay, folder, 1, ticks, dt, build / "bin")
    except measure.RunError as e:
        sys.exit(f"{scene} with {solver}: {e}")
    summary = json.loads(next((folder / "run").glob("zone_*_summary.json")).read_text())
    return figures["physics_ms"], summary["physics.solve_ms_mean"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("build", nargs="?", default=str(ROOT / "build"))
    ap.add_argument("--ticks", type=int, default=600)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scenes", default=",".join(SCENES))
    args = ap.parse_args()
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    if args.ticks < 1 or args.repeats < 1:
        sys.exit("--ticks and --repeats must be at least 1")
    scenes = [s for s in args.scenes.split(",") if s]
    for s in scenes:
        if not (ROOT / "scenes" / f"{s}.yaml").is_file():
            sys.exit(f"--scenes: no scenes/{s}.yaml")
    print(f"{args.ticks} ticks on one rank, {args.repeats} alternated rounds, medians; "
          "ms per tick", flush=True)
    print("| scene | solver | physics | solve | physics / default's |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="zs_scene_solvers_") as tmp:
        work = Path(tmp)
        for scene in scenes:
            times = {s: [] for s in SOLVERS}
            for r in range(args.repeats):
                for solver in SOLVERS:
                    times[solver].append(run(Path(args.build), scene, solver, args.ticks, work))
                print(f"  {scene}: round {r + 1} of {args.repeats}", file=sys.stderr, flush=True)
            med = {s: (statistics.median(p for p, _ in t), statistics.median(q for _, q in t))
                   for s, t in times.items()}
            base = med[SOLVERS[0]][0]
            for solver in SOLVERS:
                physics, solve = med[solver]
                name = solver + (" (default)" if solver == SOLVERS[0] else "")
                print(f"| {scene} | {name} | {physics:.3f} | {solve:.3f} | {physics / base:.2f} |",
                      flush=True)


if __name__ == "__main__":
    main()
