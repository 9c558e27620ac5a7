#!/usr/bin/python3
"""Plots broadphase_sweep's CSV: time of one findPairs against density, one panel per layout,
one line per broadphase, for the largest body count in the file.

Usage: build/bin/broadphase_sweep > sweep.csv
       /usr/bin/python3 bench/physics/plot_broadphase_sweep.py sweep.csv docs/broadphase_sweep.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KINDS = ("brute_force", "sweep_and_prune", "uniform_grid", "aabb_tree")


def main(src, out):
    rows = list(csv.DictReader(open(src)))
    n = max(int(r["bodies"]) for r in rows)
    layouts = list(dict.fromkeys(r["layout"] for r in rows))
    fig, axes = plt.subplots(1, len(layouts), figsize=(4.2 * len(layouts), 3.6), sharey=True)
    for ax, layout in zip(axes, layouts):
        sel = [r for r in rows if r["layout"] == layout and int(r["bodies"]) == n]
        dens = [float(r["density"]) for r in sel]
        for kind in KINDS:
            ax.plot(dens, [float(r[f"{kind}_ms"]) for r in sel], marker="o", label=kind)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{layout}, {n} bodies")
        ax.set_xlabel("bodies per m³ (floor: per m²)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("ms per findPairs")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
