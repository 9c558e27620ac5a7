#!/usr/bin/python3
"""Plots dr_bench's per-type sets: for NPCs, avatars and (set pertype_body) rigid bodies each,
the p99 error a client sees against the updates per entity per second it costs, one line per
dead-reckoning order through the position thresholds (the labels).

Usage: build/bin/dr_bench --only pertype --only pertype_body --csv dr_pertype.csv
       /usr/bin/python3 bench/net/plot_dr_pertype.py dr_pertype.csv docs/net_dr_pertype.png \
           ['DATA COMMAND']   (the footer names the data's command)
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from sweep_figure import plt, save  # noqa: E402


def main(src, out, data_command):
    every = list(csv.DictReader(open(src)))
    rows = [r for r in every if r["set"] == "pertype"]
    if not rows:
        sys.exit(f"{src}: no pertype rows (run dr_bench --only pertype --csv FILE)")
    body_rows = [r for r in every if r["set"] == "pertype_body"]
    panels = [("npc", "order", rows), ("avatar", "avatar_order", rows)]
    if body_rows:
        panels.append(("body", "body_order", body_rows))
    fig, axes = plt.subplots(1, len(panels), figsize=(4.75 * len(panels), 3.8))
    # Each type's own order is the one that varies for it; the other type's order does not
    # change its figures, so one of each (order, threshold) is drawn.
    for ax, (kind, order_key, kind_rows) in zip(axes, panels):
        rows = kind_rows
        lines = [(o, o, None) for o in ("static", "first", "second")]
        if kind == "body":  # rotating unless marked, and second order without the spin
            lines = [(o, o, "1") for o in ("static", "first", "second")]
            lines.append(("second", "second, no spin", "0"))
        for order, label, rotating in lines:
            pts = {}
            for r in rows:
                if r[order_key] == order and (rotating is None or r["body_rotating"] == rotating):
                    pts[float(r["threshold_m"])] = (float(r[f"updates_per_{kind}_s"]),
                                                    float(r[f"p99_{kind}_m"]))
            if not pts:
                continue
            ths = sorted(pts)
            ax.plot([pts[t][0] for t in ths], [pts[t][1] for t in ths], marker="o", label=label)
            for t in ths:
                ax.annotate(f"{t:g} m", pts[t], fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        xs = [float(r[f"updates_per_{kind}_s"]) for r in rows]
        if max(xs) > 10 * min(xs):  # log only where the costs span decades
            ax.set_xscale("log")
        ax.set_xlabel("updates per entity per second")
        ax.set_ylabel("p99 shown position error (m)")
        ax.set_title({"npc": "NPCs (waypoint walkers, 1-2 m/s)",
                      "avatar": "avatars (players' wander, 5 m/s)",
                      "body": "rigid bodies (blown-up debris)"}[kind], fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(title="order", fontsize=8)
    fig.suptitle("Dead reckoning per entity type: order and threshold (labels)", fontsize=10)
    save(fig, out, note=f"data: {data_command}" if data_command else "")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    # A data command given as an argument is in the footer's command line already.
    main(sys.argv[1], sys.argv[2], "" if len(sys.argv) > 3 else
         "build/bin/dr_bench --only pertype --only pertype_body --seconds 60 --csv FILE")
