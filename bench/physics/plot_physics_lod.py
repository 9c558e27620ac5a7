#!/usr/bin/python3
"""Plots physics_lod_sweep's CSV as work against precision: time per step against the far
bodies' error, one point per step period, for the standing pyramids (worst box drift from the
start) and the struck ones (mean distance of the far debris from where full detail put it),
with the struck run's 1 nm divergence as the floor no setting can beat.

Usage: build/bin/physics_lod_sweep --csv lod.csv
       /usr/bin/python3 bench/physics/plot_physics_lod.py lod.csv docs/physics_lod_sweep.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, out):
    rows = list(csv.DictReader(open(src)))
    fig, axes = plt.subplots(1, 2, figsize=(9.5, 3.8))
    panels = (
        ("standing", "drift", "worst box drift from its start (m)"),
        ("struck", "far_mean", "far debris: mean distance from full detail (m)"),
    )
    for ax, (run, column, label) in zip(axes, panels):
        for capped, marker in ((False, "o"), (True, "s")):
            sel = [r for r in rows if r["run"] == run and "nm" not in r["period"]
                   and ("max" in r["period"]) == capped]
            if not sel:
                continue
            # Full detail has no error against itself: a vertical line at its time instead.
            for r in sel:
                if float(r[column]) == 0.0:
                    ax.axvline(float(r["ms_per_step"]), color="black", linestyle=":",
                               label="full detail (k = 1)")
            sel = [r for r in sel if float(r[column]) > 0.0]
            ms = [float(r["ms_per_step"]) for r in sel]
            err = [float(r[column]) for r in sel]
            ax.plot(ms, err, marker=marker, linestyle="-" if not capped else "none",
                    label="longest step capped" if capped else "period k, no cap")
            for r, x, y in zip(sel, ms, err):
                ax.annotate(f"every {r['period']}", (x, y), textcoords="offset points",
                            xytext=(4, 4), fontsize=8)
        floor = [r for r in rows if r["run"] == run and "nm" in r["period"]]
        if floor and float(floor[0][column]) > 0:
            ax.axhline(float(floor[0][column]), color="grey", linestyle="--",
                       label="full detail, balls moved 1 nm")
        ax.legend(loc="upper right", fontsize=8)
        ax.set_yscale("log")
        ax.set_xlabel("ms per step (whole world)")
        ax.set_ylabel(label)
        ax.set_title(f"many_pyramids, {run}")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
