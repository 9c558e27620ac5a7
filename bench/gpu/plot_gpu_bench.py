#!/usr/bin/env python3
"""Draws gpu_bench's CSV: ms per tick against N, CPU (double) and OpenCL (float), one panel per
workload, with the float-versus-double median error written next to each OpenCL point.

usage: plot_gpu_bench.py bench.csv out.png
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")  # no display on build machines
import matplotlib.pyplot as plt


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = defaultdict(list)
    with open(argv[1], newline="") as f:
        for r in csv.DictReader(f):
            rows[r["workload"]].append(r)
    fig, axes = plt.subplots(1, len(rows), figsize=(4.2 * len(rows), 3.6), squeeze=False)
    for ax, (workload, rs) in zip(axes[0], rows.items()):
        rs.sort(key=lambda r: int(r["n"]))
        n = [int(r["n"]) for r in rs]
        ax.loglog(n, [float(r["cpu_ms"]) for r in rs], "o-", label="CPU, double")
        ocl = [float(r["opencl_ms"]) for r in rs]
        ax.loglog(n, ocl, "s-", label="OpenCL (PoCL), float")
        for x, y, r in zip(n, ocl, rs):
            ax.annotate(f"{float(r['median_error_m']):.0e} m", (x, y), fontsize=7,
                        textcoords="offset points", xytext=(4, -10))
        ax.set_title(workload)
        ax.set_xlabel("N")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("ms per tick")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=90)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
