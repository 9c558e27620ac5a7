#!/usr/bin/env python3
"""The halo skin knob (issue 19): what the skin trades, rebuilding the send lists against
sending more ghosts, and that every skin gives the same result.

The halo's send lists name the entities within width + skin of each neighbour's zone; they are
reused until this rank's entities change, the borders move, or an entity moved more than
skin/2 since they were built (zone_node/cluster/halo.h, LAMMPS' neighbour skin). A skin of 0
rebuilds them whenever anything moved; a wide one keeps them and forwards ghosts nobody reads.

scenes/crowd_flock.yaml (3000 flockers, reach 3 m, halo.width 3, 2x2 zones) runs on 4 ranks with
halo.skin S for each S in SKINS (the default is max(1 m, width/5) = 1 m), TICKS ticks, --gpu off.
Per skin: the share of ticks that rebuilt the lists (mean over the zones), ghosts sent and halo
bytes per tick (summed over the zones), the halo stage's mean ms, the wall ms per tick and the
median tick ms (slowest rank; each the median of --repeat runs, since 4 ranks share 2 cores
here), and whether the final state equals the 1-rank run's bit for bit.

Usage: bench/cluster/halo_skin.py [TICKS] [--repeat N] [--plot PNG]   (default 300; ZONESIM_BIN=build/bin)
"""
import argparse
import statistics
import sys
import tempfile
from pathlib import Path

from halo_width import ROOT, SCENE, finish_plot, run

SKINS = (0, 0.1, 0.25, 0.5, 1, 2, 4, 8)


def plot(rows, ticks, path):
    sys.path.insert(0, str(ROOT / "bench"))
    from sweep_figure import plt
    skins = [r["skin"] for r in rows]
    fig, (work, time) = plt.subplots(1, 2, figsize=(10, 4))
    work.plot(skins, [r["rebuilt"] * 100 for r in rows], "o-", label="ticks that rebuilt lists, %")
    work.set_ylabel("ticks that rebuilt the send lists, %")
    sent = work.twinx()
    sent.plot(skins, [r["sent"] for r in rows], "s--", color="tab:red", label="ghosts sent / tick")
    sent.set_ylabel("ghosts sent per tick (sum over 4 zones)", color="tab:red")
    work.legend(loc="center right", fontsize=8)
    finish_plot(fig, (work, time), rows, "skin", "halo.skin, m (width 3 m; default 1 m)", ticks,
                path, symlog=True)


def main():
    args = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    args.add_argument("ticks", nargs="?", type=int, default=300)
    args.add_argument("--repeat", type=int, default=3, help="runs per skin (times: median)")
    args.add_argument("--plot", help="write the work-precision plot here (PNG)")
    opts = args.parse_args()
    ticks = opts.ticks
    rows = []
    with tempfile.TemporaryDirectory(prefix="zs_skin_") as tmp:
        reference, _ = run(SCENE, 1, tmp, "one_rank", ticks)
        print(f"crowd_flock, halo.width 3, 4 ranks, {ticks} ticks; sums over the 4 zones, per tick")
        print("| halo skin m | ticks rebuilt % | ghosts sent | halo KiB | halo ms (slowest) | "
              "wall ms/tick | tick ms p50 | final state = 1 rank |")
        print("|---|---|---|---|---|---|---|---|")
        for skin in SKINS:
            text = SCENE.read_text().replace("halo:\n  width: 3",
                                             f"halo:\n  width: 3\n  skin: {skin}")
            assert text != SCENE.read_text(), "scenes/crowd_flock.yaml's halo block changed"
            scene = Path(tmp) / f"skin_{skin}.yaml"
            scene.write_text(text)
            runs = [run(scene, 4, tmp, f"s{skin}", ticks) for _ in range(opts.repeat)]
            dump, zones = runs[0]

            def median(time):  # of the slowest rank's, over the runs
                return statistics.median(max(time(z) for z in zs) for _, zs in runs)
            rebuilt = sum(z["halo_rebuilds"] for z in zones) / len(zones) / ticks
            sent = sum(z["ghosts_sent"] for z in zones) / ticks
            kib = sum(z["halo_bytes"] for z in zones) / ticks / 1024
            halo_ms = median(lambda z: z["halo_ms_mean"])
            tick_mean = median(lambda z: z["wall_s"] * 1e3 / ticks)
            tick_ms = median(lambda z: z["tick_ms_p50"])
            same = all(d == reference for d, _ in runs)
            print(f"| {skin:g} | {100 * rebuilt:.0f} | {sent:.0f} | {kib:.1f} | {halo_ms:.3f} | "
                  f"{tick_mean:.2f} | {tick_ms:.2f} | {'yes' if same else 'NO'} |", flush=True)
            rows.append(dict(skin=skin, rebuilt=rebuilt, sent=sent, kib=kib, halo_ms=halo_ms,
                             tick_ms=tick_ms, same=same))
    if opts.plot:
        plot(rows, ticks, opts.plot)


if __name__ == "__main__":
    main()
