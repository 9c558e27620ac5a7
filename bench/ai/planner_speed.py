#!/usr/bin/env python3
"""Time per path of the optimal grid planners on the shipped Moving AI maps, as a table.

    planner_speed.py [--bin build/bin] [--runs 2] [--landmarks 8] [--maps maze512-1-0 ...]

Runs `scen_check MAP MAP.scen --planner P [--landmarks K]` over every problem of each file,
the planners alternating within each run (so a busy machine slows them alike), and prints per
map and planner the µs per path of each run and the speed-up over A* (octile estimate) of the
same run. Any mismatch against the listed optima fails the run. Landmark tables are built
before scen_check's clock starts; their build time and memory are printed beside.
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MAPS = ["8room_000", "maze512-1-0", "random512-10-0"]


def run(bin_dir, map_name, planner, landmarks):
    data = ROOT / "tests" / "data" / "movingai"
    cmd = [str(Path(bin_dir) / "scen_check"), str(data / f"{map_name}.map"),
           str(data / f"{map_name}.map.scen"), "--planner", planner]
    if landmarks:
        cmd += ["--landmarks", str(landmarks)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({out.returncode}): {out.stderr.strip()}")
    fields = dict(re.findall(r"(\w+) (\S+)", out.stdout))
    if fields.get("mismatches") != "0":
        sys.exit(f"{' '.join(cmd)}: {fields.get('mismatches')} mismatches")
    return fields


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=str(ROOT / "build" / "bin"))
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--landmarks", type=int, default=8)
    ap.add_argument("--maps", nargs="+", default=MAPS)
    args = ap.parse_args()
    k = args.landmarks
    variants = [("astar", 0), ("jps", 0), ("astar", k), ("jps", k), ("jps+", k)]
    times = {}  # (map, variant) -> [us per run]
    extra = {}
    for r in range(args.runs):
        for m in args.maps:
            for v in variants:
                f = run(args.bin, m, *v)
                times.setdefault((m, v), []).append(float(f["us_per_path"]))
                if v[1]:
                    extra[m] = (f["landmarks_ms"], f["landmarks_mb"])
                print(f"run {r + 1}/{args.runs} {m} {v[0]}{' +' + str(v[1]) + ' landmarks' if v[1] else ''}: "
                      f"{f['us_per_path']} us/path", file=sys.stderr, flush=True)
    runs = " / ".join(str(i + 1) for i in range(args.runs))
    print(f"| map | planner | µs/path, runs {runs} | speed-up over A*, runs {runs} |")
    print("|---|---|---|---|")
    for m in args.maps:
        base = times[(m, ("astar", 0))]
        for v in variants:
            t = times[(m, v)]
            name = v[0] + (f" + {v[1]} landmarks" if v[1] else "")
            print(f"| {m if v == variants[0] else ''} | {name} | "
                  f"{' / '.join(f'{x:.0f}' for x in t)} | "
                  f"{' / '.join(f'{b / x:.1f}x' for b, x in zip(base, t))} |")
    for m, (ms, mb) in extra.items():
        print(f"\n{m}: {k} landmarks built in {ms} ms, {mb} MB", end="")
    print()


if __name__ == "__main__":
    main()
