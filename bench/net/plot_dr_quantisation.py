#!/usr/bin/python3
"""Plots dr_bench's quantisation rows (--only quant): bits per visible entity and the shown
position error (p50, p99) against the wire's position resolution.
Usage: dr_bench --only quant --csv q.csv; plot_dr_quantisation.py q.csv docs/net_dr_quantisation.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["set"] == "quant"]
res = [1000 * float(r["position_resolution_m"]) for r in rows]
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
a.plot(res, [float(r["bps_per_visible"]) for r in rows], marker="o", label="payload")
a.plot(res, [float(r["wire_bps_per_visible"]) for r in rows], marker="s", label="on the wire")
for r, x in zip(rows, res):
    a.annotate(f"{r['rotation_bits']} rot bits", (x, float(r["bps_per_visible"])), fontsize=7,
               textcoords="offset points", xytext=(3, -10))
a.set_xscale("log")
a.set_xlabel("position resolution, mm")
a.set_ylabel("bits/s per visible moving entity")
a.legend(fontsize=8)
a.grid(True, which="both", alpha=0.3)
b.plot(res, [1000 * float(r["p50_m"]) for r in rows], marker="o", label="p50")
b.plot(res, [1000 * float(r["p99_m"]) for r in rows], marker="^", label="p99")
b.set_xscale("log")
b.set_yscale("log")
b.set_xlabel("position resolution, mm")
b.set_ylabel("shown position error, mm")
b.legend(fontsize=8)
b.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print(f"wrote {sys.argv[2]}")
