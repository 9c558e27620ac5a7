#!/usr/bin/env python3
"""The halo width knob (issue 19): what a wider halo costs, and that any width at least the
flock's reach gives the same result.

scenes/crowd_flock.yaml (3000 flockers, reach 3 m, 2x2 zones) runs on 4 ranks with
halo.width W for each W in WIDTHS (the loader refuses W below the reach), TICKS ticks, --gpu
off. Per width: ghosts held and sent per tick and halo bytes per tick (summed over the zones),
the halo stage's and the tick's mean ms (slowest rank), and whether the final state equals
the 1-rank run's bit for bit.

Usage: bench/cluster/halo_width.py [TICKS] [--plot PNG]   (default 300; ZONESIM_BIN=build/bin)
The plot (bench/sweep_figure.py) draws ghosts and bytes, and the stage times, against the
width, each point marked by whether the run equals the 1-rank run.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ZONESIM_BIN", ROOT / "build" / "bin"))
WIDTHS = (3, 4, 6, 10, 15, 20)
SCENE = ROOT / "scenes/crowd_flock.yaml"


def run(scene, ranks, tmp, tag, ticks):
    """Runs `scene` on `ranks` ranks; its final state (text) and each zone's summary."""
    dump = Path(tmp) / f"{tag}.jsonl"
    metrics = Path(tmp) / f"m_{tag}"
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), str(BIN / "zone_node"),
                    "--scene", str(scene), "--ticks", str(ticks), "--no-dds", "--gpu", "off",
                    "--dump-state", str(dump), "--metrics", str(metrics), "--log-level", "warn"],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    zones = [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]
    return dump.read_text(), zones


def plot(rows, ticks, path):
    sys.path.insert(0, str(ROOT / "bench"))
    from sweep_figure import plt
    widths = [r["width"] for r in rows]
    fig, (work, time) = plt.subplots(1, 2, figsize=(10, 4))
    work.plot(widths, [r["sent"] for r in rows], "o-", label="ghosts sent / tick")
    work.plot(widths, [r["held"] for r in rows], "s--", label="ghosts held at the end")
    work.set_ylabel("ghosts (sum over the 4 zones)")
    kib = work.twinx()
    kib.plot(widths, [r["kib"] for r in rows], "^:", color="tab:red", label="halo KiB / tick")
    kib.set_ylabel("halo KiB per tick", color="tab:red")
    work.legend(loc="upper left", fontsize=8)
    finish_plot(fig, (work, time), rows, "width", "halo.width, m (the flock's reach is 3 m)",
                ticks, path)


def finish_plot(fig, axes, rows, knob, xlabel, ticks, path, symlog=False):
    """What the halo sweeps' figures share (halo_width.py, halo_skin.py): the right panel's
    halo stage and tick times, the x axes, a red line at each setting whose final state is not
    the 1-rank run's, the title; then writes the figure."""
    from sweep_figure import save
    work, time = axes
    xs = [r[knob] for r in rows]
    time.plot(xs, [r["halo_ms"] for r in rows], "o-", label="halo stage, mean")
    time.plot(xs, [r["tick_ms"] for r in rows], "s--", label="tick, median")
    time.set_ylabel("ms (slowest of 4 ranks on 2 shared cores)")
    time.legend(fontsize=8)
    for ax in (work, time):
        if symlog:
            ax.set_xscale("symlog", linthresh=0.1)
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
        for r in rows:
            if not r["same"]:
                ax.axvline(r[knob], color="tab:red", alpha=0.3)
    every = f"every {knob}" if all(r["same"] for r in rows) else f"only unmarked {knob}s"
    fig.suptitle(f"halo {knob} on crowd_flock, 4 ranks, {ticks} ticks: final state equals the "
                 f"1-rank run bit for bit at {every}", fontsize=10)
    save(fig, path)


def main():
    args = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    args.add_argument("ticks", nargs="?", type=int, default=300)
    args.add_argument("--plot", help="write the work-precision plot here (PNG)")
    opts = args.parse_args()
    ticks = opts.ticks
    rows = []
    with tempfile.TemporaryDirectory(prefix="zs_halo_") as tmp:
        reference, _ = run(SCENE, 1, tmp, "one_rank", ticks)
        print(f"crowd_flock, 4 ranks, {ticks} ticks; sums over the 4 zones, per tick")
        print("| halo width m | ghosts held | ghosts sent | halo KiB | halo ms (slowest) | "
              "tick ms (slowest) | final state = 1 rank |")
        print("|---|---|---|---|---|---|---|")
        for w in WIDTHS:
            text = SCENE.read_text().replace("halo:\n  width: 3", f"halo:\n  width: {w}")
            scene = Path(tmp) / f"halo_{w}.yaml"
            scene.write_text(text)
            dump, zones = run(scene, 4, tmp, f"w{w}", ticks)
            ghosts = sum(z["ghosts"] for z in zones) / 1  # held at the end (a level)
            sent = sum(z["ghosts_sent"] for z in zones) / ticks
            kib = sum(z["halo_bytes"] for z in zones) / ticks / 1024
            halo_ms = max(z["halo_ms_mean"] for z in zones)
            tick_ms = max(z["tick_ms_p50"] for z in zones)
            print(f"| {w} | {ghosts:.0f} | {sent:.0f} | {kib:.1f} | {halo_ms:.3f} | "
                  f"{tick_ms:.2f} | {'yes' if dump == reference else 'NO'} |", flush=True)
            rows.append(dict(width=w, held=ghosts, sent=sent, kib=kib, halo_ms=halo_ms,
                             tick_ms=tick_ms, same=dump == reference))
    if opts.plot:
        plot(rows, ticks, opts.plot)


if __name__ == "__main__":
    main()
