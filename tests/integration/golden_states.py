"""Final entity states of every shipped scene, for proving that a change changes no behaviour.

    golden_states.py dump OUT_DIR [--bin BIN_DIR] [--ticks N] [--only SCENE...]
        runs every scenes/*.yaml for N ticks (default 600) on 1 and 4 ranks, --no-dds,
        --gpu off, and writes OUT_DIR/<scene>_<ranks>.jsonl (zone_node --dump-state: id, kind,
        position, velocity, orientation of every entity and live particle, %.17g).
    golden_states.py compare A_DIR B_DIR
        compares two such folders file by file, byte for byte; prints the first differing
        entity of each scene that differs and exits 1 if any does.

Typical use, the commit before a change against the commit after:

    git worktree add /tmp/before BASE && (cd /tmp/before && cmake -S . -B build -G Ninja &&
        cmake --build build)
    python3 tests/integration/golden_states.py dump /tmp/gold_before --bin /tmp/before/build/bin
    python3 tests/integration/golden_states.py dump /tmp/gold_after --bin build/bin
    python3 tests/integration/golden_states.py compare /tmp/gold_before /tmp/gold_after
"""
import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import harness as h

RANKS = (1, 4)


def shipped_scenes():
    root = h.SOURCE_DIR / "scenes"
    return sorted(root.glob("*.yaml"))  # scenes/ai/ holds machine definitions, not scenes


def scene_key(path):
    return str(path.relative_to(h.SOURCE_DIR / "scenes").with_suffix("")).replace("/", "__")


def dump(out, bin_dir, ticks, only):
    out.mkdir(parents=True, exist_ok=True)
    scenes = [p for p in shipped_scenes() if not only or scene_key(p) in only]
    if only and len(scenes) != len(only):
        known = {scene_key(p) for p in shipped_scenes()}
        sys.exit(f"golden_states: unknown scene(s): {sorted(set(only) - known)}")
    env = h.base_env()
    for n, scene in enumerate(scenes, 1):
        key = scene_key(scene)
        for ranks in RANKS:
            target = out / f"{key}_{ranks}.jsonl"
            log = out / f"{key}_{ranks}.log"
            t0 = time.time()
            cmd = h.mpirun(ranks, bin_dir / "zone_node", "--scene", scene, "--ticks", ticks,
                           "--no-dds", "--gpu", "off", "--dump-state", target)
            with open(log, "w") as f:
                rc = subprocess.run(list(map(str, cmd)), stdout=f, stderr=subprocess.STDOUT,
                                    env=env, timeout=900).returncode
            if rc != 0:
                sys.exit(f"golden_states: {key} on {ranks} ranks failed (exit {rc}):\n"
                         f"{h.tail(log)}")
            lines = target.read_text().count("\n")
            print(f"[{n}/{len(scenes)}] {key} on {ranks} ranks: {lines} entities, "
                  f"{time.time() - t0:.1f} s", flush=True)


def first_difference(a, b):
    la, lb = a.read_text().splitlines(), b.read_text().splitlines()
    for x, y in zip(la, lb):
        if x != y:
            return f"first difference:\n  before {x}\n  after  {y}"
    return f"{len(la)} entities before, {len(lb)} after"


def compare(a_dir, b_dir):
    names = lambda d: {p.name for p in d.iterdir() if p.suffix == ".jsonl"}
    a_names, b_names = names(a_dir), names(b_dir)
    bad = 0
    for name in sorted(a_names ^ b_names):
        print(f"MISSING {name}: only in {a_dir if name in a_names else b_dir}")
        bad += 1
    same = 0
    for name in sorted(a_names & b_names):
        a, b = a_dir / name, b_dir / name
        if a.read_bytes() == b.read_bytes():
            same += 1
            continue
        bad += 1
        print(f"DIFFERS {name}: {first_difference(a, b)}")
    entities = sum((a_dir / n).read_text().count("\n") for n in a_names & b_names
                   if n.endswith(".jsonl"))
    print(f"golden states: {same} identical, {bad} different or missing "
          f"({entities} entity lines compared)")
    return 1 if bad else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    d = sub.add_parser("dump")
    d.add_argument("out", type=Path)
    d.add_argument("--bin", type=Path, default=h.bin_dir())
    d.add_argument("--ticks", type=int, default=600)
    d.add_argument("--only", nargs="*", default=[])
    c = sub.add_parser("compare")
    c.add_argument("a", type=Path)
    c.add_argument("b", type=Path)
    args = parser.parse_args()
    if args.command == "dump":
        if not (args.bin / "zone_node").exists():
            sys.exit(f"golden_states: no zone_node in {args.bin}")
        dump(args.out, args.bin.resolve(), args.ticks, set(args.only))
        return 0
    return compare(args.a, args.b)


if __name__ == "__main__":
    sys.exit(main())
