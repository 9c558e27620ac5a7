#!/usr/bin/env python3
"""Plots work_precision's CSV: error against run time (log-log) per integrator and problem,
and stack drift against solver cost. Usage: plot_work_precision.py data.csv out.png"""
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main(path, out):
    curves = defaultdict(list)
    solver = defaultdict(list)
    methods = defaultdict(list)
    for line in open(path):
        f = line.strip().split(",")
        if f[0] == "integrator" and f[1] != "problem":
            curves[(f[1], f[2])].append((float(f[4]), max(float(f[5]), 1e-16)))
        elif f[0] == "solver" and f[2] != "iterations":
            solver[int(f[3])].append((float(f[4]), max(float(f[5]), 1e-6), int(f[2])))
        elif f[0] == "method" and f[2] != "kind":
            methods[f[2]].append((int(f[3]), max(float(f[5]), 1e-6)))
    problems = sorted({p for p, _ in curves})
    panels = len(problems) + 1 + (1 if methods else 0)
    fig, axes = plt.subplots(1, panels, figsize=(6 * panels, 4.5))
    for ax, problem in zip(axes, problems):
        for (p, kind), pts in sorted(curves.items()):
            if p != problem:
                continue
            pts.sort()
            ax.loglog([t for t, _ in pts], [e for _, e in pts], marker="o", label=kind)
        ax.set_title(problem)
        ax.set_xlabel("seconds per run")
        ax.set_ylabel("position error (m)")
        ax.legend(fontsize=7)
    if methods:
        ax = axes[-1]
        for kind, pts in sorted(methods.items()):
            pts.sort()
            ax.loglog([i for i, _ in pts], [d for _, d in pts], marker="o", label=kind)
        ax.set_title("5-box column, 10 s at 1/60 s: drift against iterations")
        ax.set_xlabel("velocity iterations (soft step: 2 per sub-step)")
        ax.set_ylabel("largest drift (m, 1 = fell)")
        ax.legend(fontsize=7)
    ax = axes[len(problems)]
    for substeps, pts in sorted(solver.items()):
        pts.sort()
        ax.loglog([t for t, _, _ in pts], [d for _, d, _ in pts], marker="o",
                  label=f"{substeps} substep(s)")
        for t, d, it in pts:
            ax.annotate(str(it), (t, d), fontsize=7)
    ax.set_title("10-box stack, 10 s: drift against cost (labels: iterations)")
    ax.set_xlabel("ms per step")
    ax.set_ylabel("largest drift (m)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
