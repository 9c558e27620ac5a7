#!/usr/bin/env python3
"""Flow fields stored with the map (map.fields) against fields built at start (issue 18).

For the shipped courtyard and the three 512 x 512 Moving AI maps in tests/data, a scene with a
flow crowd of 2000 NPCs heading to 4 destinations (open cells near the map's corners, found
here) is baked with build/bin/bake_fields, which prints the fields' memory, the file's size, and
the build and read times of the fields alone. Then zone_node runs the scene for TICKS ticks with
fields built at start and with the baked file, alternating REPEATS times: start-up time (wall
seconds of the run minus its ticks' time) and the mean tick, medians over the repeats.

Usage: bench/crowd/baked_fields.py [TICKS [REPEATS]]   (defaults 200, 3; ZONESIM_BIN=build/bin)
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
TICKS = int(sys.argv[1]) if len(sys.argv) > 1 else 200
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 3
MAPS = [ROOT / "scenes/maps/courtyard.map"] + sorted((ROOT / "tests/data/movingai").glob("*.map"))


def read_map(path):
    lines = path.read_text().splitlines()
    h = int(lines[1].split()[1])
    w = int(lines[2].split()[1])
    return w, h, lines[4:4 + h]


def open_cell_near(rows, w, h, fx, fy):
    """The open cell nearest (fx w, fy h), searching outwards ring by ring."""
    cx, cy = int(fx * (w - 1)), int(fy * (h - 1))
    for r in range(max(w, h)):
        for y in range(max(0, cy - r), min(h, cy + r + 1)):
            for x in range(max(0, cx - r), min(w, cx + r + 1)):
                if rows[y][x] in ".GS":
                    return x, y
    raise SystemExit("no open cell")


def scene_text(map_path, fields, w, h, rows):
    goals = [open_cell_near(rows, w, h, fx, fy)
             for fx, fy in ((0.1, 0.1), (0.9, 0.1), (0.1, 0.9), (0.9, 0.9))]
    dest = ", ".join(f"[{x + 0.5}, 0, {y + 0.5}]" for x, y in goals)
    text = f"""world: {{min: [0, 0, 0], max: [{w}, 20, {h}]}}
tick: {{dt: 0.05}}
seed: 5
zones: {{columns: 1, rows: 1}}
halo: {{width: 4}}
map: {{file: {map_path}, cell_size: 1.0{", fields: " + str(fields) if fields else ""}}}
populations:
  - kind: npc
    count: 2000
    flow: {{destinations: [{dest}]}}
"""
    return text


def zone_run(scene, tmp, tag):
    metrics = Path(tmp) / f"m_{tag}"
    t0 = time.perf_counter()
    subprocess.run([str(BIN / "zone_node"), "--scene", str(scene), "--ticks", str(TICKS),
                    "--no-dds", "--gpu", "off", "--metrics", str(metrics), "--log-level", "warn"],
                   check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    s = json.loads((metrics / "zone_0_summary.json").read_text())
    return wall - s["wall_s"], s["tick_ms_p50"]


def main():
    print("| map | cells | fields | memory KiB | file KiB | bake: build ms | bake: read ms | "
          "zone start s, built | loaded | tick p50 ms, built | loaded |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="zs_baked_") as tmp:
        for m in MAPS:
            w, h, rows = read_map(m)
            fields = Path(tmp) / f"{m.stem}.fields"
            built = Path(tmp) / f"{m.stem}_built.yaml"
            loaded = Path(tmp) / f"{m.stem}_loaded.yaml"
            built.write_text(scene_text(m, None, w, h, rows))
            loaded.write_text(scene_text(m, fields, w, h, rows))
            out = subprocess.run([str(BIN / "bake_fields"), str(built), "--out", str(fields)],
                                 check=True, capture_output=True, text=True).stdout
            # "... N fields on W x H cells, B bytes in memory, file F bytes; built in X ms, read
            # back in Y ms (Zx)"
            words = out.replace(",", "").replace(";", "").split()
            count = int(words[1])
            memory = int(words[words.index("bytes") - 1])
            file_bytes = int(words[words.index("file") + 1])
            build_ms = float(words[words.index("built") + 2])
            read_ms = float(words[words.index("read") + 3])
            starts = {"built": [], "loaded": []}
            ticks = {"built": [], "loaded": []}
            for r in range(REPEATS):
                for tag, scene in (("built", built), ("loaded", loaded)):
                    start, tick = zone_run(scene, tmp, f"{m.stem}_{tag}_{r}")
                    starts[tag].append(start)
                    ticks[tag].append(tick)
            med = statistics.median
            print(f"| {m.name} | {w}x{h} | {count} | {memory / 1024:.0f} | {file_bytes / 1024:.0f} "
                  f"| {build_ms:.1f} | {read_ms:.1f} | {med(starts['built']):.3f} | "
                  f"{med(starts['loaded']):.3f} | {med(ticks['built']):.2f} | "
                  f"{med(ticks['loaded']):.2f} |", flush=True)


if __name__ == "__main__":
    main()
