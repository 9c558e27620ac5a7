#!/usr/bin/python3
"""Plots dr_bench's per-type set: for NPCs and avatars each, the p99 error a client sees
against the updates per entity per second it costs, one line per dead-reckoning order through
the position thresholds (the labels).

Usage: build/bin/dr_bench --only pertype --csv dr_pertype.csv
       /usr/bin/python3 bench/net/plot_dr_pertype.py dr_pertype.csv docs/net_dr_pertype.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, out):
    rows = [r for r in csv.DictReader(open(src)) if r["set"] == "pertype"]
    if not rows:
        sys.exit(f"{src}: no pertype rows (run dr_bench --only pertype --csv FILE)")
    fig, axes = plt.subplots(1, 2, figsize=(9.5, 3.8))
    # Each type's own order is the one that varies for it; the other type's order does not
    # change its figures, so one of each (order, threshold) is drawn.
    for ax, (kind, order_key) in zip(axes, (("npc", "order"), ("avatar", "avatar_order"))):
        for order in ("static", "first", "second"):
            pts = {}
            for r in rows:
                if r[order_key] == order:
                    pts[float(r["threshold_m"])] = (float(r[f"updates_per_{kind}_s"]),
                                                    float(r[f"p99_{kind}_m"]))
            if not pts:
                continue
            ths = sorted(pts)
            ax.plot([pts[t][0] for t in ths], [pts[t][1] for t in ths], marker="o", label=order)
            for t in ths:
                ax.annotate(f"{t:g} m", pts[t], fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        xs = [float(r[f"updates_per_{kind}_s"]) for r in rows]
        if max(xs) > 10 * min(xs):  # log only where the costs span decades
            ax.set_xscale("log")
        ax.set_xlabel("updates per entity per second")
        ax.set_ylabel("p99 shown position error (m)")
        ax.set_title({"npc": "NPCs (waypoint walkers, 1-2 m/s)",
                      "avatar": "avatars (players' wander, 5 m/s)"}[kind])
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(title="order", fontsize=8)
    fig.suptitle("Dead reckoning per entity type: order and threshold (labels)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
