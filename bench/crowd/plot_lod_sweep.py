#!/usr/bin/python3
"""Plots the LOD bands' work-precision sweep: for each crowd and agent kind, the time saved
against full detail (speed-up) and the outcome's drift, one line per near radius through the
far periods, so the cheapest bands within an error budget can be read off.

Usage: build/bin/crowd_bench --only lod-sweep --agents 10000 --lod-seconds 120 > flow.csv
       build/bin/group_lod_bench --sweep --formations 20 --ants 2000 --seconds 240 > groups.csv
       build/bin/agent_bench --lod-sweep --ticks 100 --sizes 10000 > agents.csv
       /usr/bin/python3 bench/crowd/plot_lod_sweep.py docs/lod_bands_sweep.png flow.csv groups.csv agents.csv
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FIELDS = ["kind", "agents", "near_radius", "far_radius", "far_every", "ms_per_tick", "speedup",
          "updates_ratio", "error_name", "error"]
UNITS = {"arrival_drift_s": "mean arrival time drift (s)", "slot_error_m": "mean slot error (m)",
         "route_change": "relative change of the colony's route",
         "end_pos_error_m": "mean end position drift (m)"}


def read(paths):
    rows = []
    for path in paths:
        for row in csv.reader(open(path)):
            if len(row) == len(FIELDS) and row[0] != "kind":
                rows.append(dict(zip(FIELDS, row)))
    return rows


def main(out, paths):
    rows = read(paths)
    kinds = list(dict.fromkeys(r["kind"] for r in rows))
    if not kinds:
        sys.exit("no sweep rows in " + ", ".join(paths))
    cols = min(3, len(kinds))
    nrows = (len(kinds) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.8 * nrows), squeeze=False)
    for ax, kind in zip(axes.flat, kinds):
        sel = [r for r in rows if r["kind"] == kind]
        for near in dict.fromkeys(r["near_radius"] for r in sel):
            line = sorted((r for r in sel if r["near_radius"] == near),
                          key=lambda r: int(r["far_every"]))
            xs = [float(r["speedup"]) for r in line]
            ys = [float(r["error"]) for r in line]
            ax.plot(xs, ys, marker="o", label=f"near {near} m")
            for r, x, y in zip(line, xs, ys):
                ax.annotate(r["far_every"], (x, y), fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        ax.set_title(f"{kind}, {sel[0]['agents']} agents")
        ax.set_xlabel("speed-up against full detail")
        ax.set_ylabel(UNITS.get(sel[0]["error_name"], sel[0]["error_name"]))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(kinds):]:
        ax.axis("off")
    fig.suptitle("LOD bands: time against outcome (labels: far period in ticks)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
