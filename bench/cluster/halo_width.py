#!/usr/bin/env python3
"""The halo width knob (issue 19): what a wider halo costs, and that any width at least the
flock's reach gives the same result.

scenes/crowd_flock.yaml (3000 flockers, reach 3 m, 2x2 zones) runs on 4 ranks with
halo.width W for each W in WIDTHS (the loader refuses W below the reach), TICKS ticks, --gpu
off. Per width: ghosts held and sent per tick and halo bytes per tick (summed over the zones),
the halo stage's and the tick's mean ms (slowest rank), and whether the final state equals
the 1-rank run's bit for bit.

Usage: bench/cluster/halo_width.py [TICKS]   (default 300; ZONESIM_BIN=build/bin)
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
TICKS = int(sys.argv[1]) if len(sys.argv) > 1 else 300
WIDTHS = (3, 4, 6, 10, 15, 20)
SCENE = ROOT / "scenes/crowd_flock.yaml"


def run(scene, ranks, tmp, tag):
    dump = Path(tmp) / f"{tag}.jsonl"
    metrics = Path(tmp) / f"m_{tag}"
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), str(BIN / "zone_node"),
                    "--scene", str(scene), "--ticks", str(TICKS), "--no-dds", "--gpu", "off",
                    "--dump-state", str(dump), "--metrics", str(metrics), "--log-level", "warn"],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    zones = [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]
    return dump.read_text(), zones


def main():
    with tempfile.TemporaryDirectory(prefix="zs_halo_") as tmp:
        reference, _ = run(SCENE, 1, tmp, "one_rank")
        print(f"crowd_flock, 4 ranks, {TICKS} ticks; sums over the 4 zones, per tick")
        print("| halo width m | ghosts held | ghosts sent | halo KiB | halo ms (slowest) | "
              "tick ms (slowest) | final state = 1 rank |")
        print("|---|---|---|---|---|---|---|")
        for w in WIDTHS:
            text = SCENE.read_text().replace("halo:\n  width: 3", f"halo:\n  width: {w}")
            scene = Path(tmp) / f"halo_{w}.yaml"
            scene.write_text(text)
            dump, zones = run(scene, 4, tmp, f"w{w}")
            ghosts = sum(z["ghosts"] for z in zones) / 1  # held at the end (a level)
            sent = sum(z["ghosts_sent"] for z in zones) / TICKS
            kib = sum(z["halo_bytes"] for z in zones) / TICKS / 1024
            halo_ms = max(z["halo_ms_mean"] for z in zones)
            tick_ms = max(z["tick_ms_p50"] for z in zones)
            print(f"| {w} | {ghosts:.0f} | {sent:.0f} | {kib:.1f} | {halo_ms:.3f} | "
                  f"{tick_ms:.2f} | {'yes' if dump == reference else 'NO'} |", flush=True)


if __name__ == "__main__":
    main()
