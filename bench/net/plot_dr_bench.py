#!/usr/bin/python3
"""Plots dr_bench's CSV: payload bits/s per client against the p99 client-side position error
for each dead-reckoning order over the threshold sweep, with the 10 % loss rows (first order,
0.25 m: no resend, resend until acknowledged, 1 s heartbeat) as separate points, and bandwidth
against interest radius.
Usage: plot_dr_bench.py dr_bench.csv docs/net_dr_tradeoff.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
for order, marker in (("static", "s"), ("first", "o"), ("second", "^")):
    sweep = [r for r in rows if r["set"] == "sweep" and r["order"] == order]
    x = [float(r["p99_m"]) for r in sweep]
    y = [float(r["bps_per_visible"]) for r in sweep]
    a.plot(x, y, marker=marker, label=f"{order} order")
    for r, xi, yi in zip(sweep, x, y):
        a.annotate(f"{float(r['threshold_m']):g} m", (xi, yi), fontsize=7,
                   textcoords="offset points", xytext=(3, 3))
loss_labels = {"loss10": "10% loss, no resend", "loss10r": "10% loss, resend until acked",
               "hb1s": "10% loss, 1 s heartbeat"}
for (name, label), marker in zip(loss_labels.items(), ("X", "P", "D")):
    for r in (r for r in rows if r["set"] == name):
        a.plot([float(r["p99_m"])], [float(r["bps_per_visible"])], marker=marker, ls="none",
               color="black", label=label)
a.axhline(300, color="grey", ls="--", lw=1)
a.text(0.02, 320, "Fiedler: ~300 bit/s per cube", fontsize=8, color="grey")
a.set_xscale("log")
a.set_yscale("log")
a.set_xlabel("p99 error of the shown position (m)")
a.set_ylabel("payload bit/s per visible moving entity")
a.set_title("Bandwidth against error, threshold sweep")
a.set_ylim(top=4e4)  # room for the legend above the static curve
a.legend(fontsize=8, loc="upper right")
radius = [r for r in rows if r["set"] == "radius"]
b.plot([float(r["radius_m"]) for r in radius], [float(r["payload_bps"]) / 1000 for r in radius],
       marker="o", label="payload")
b.plot([float(r["radius_m"]) for r in radius], [float(r["wire_bps"]) / 1000 for r in radius],
       marker="s", label="with framing + UDP/IP headers")
b.set_xlabel("interest radius (m)")
b.set_ylabel("kbit/s per client")
b.set_title("Interest radius against bandwidth (first order, 0.25 m)")
b.legend()
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print("wrote", sys.argv[2])
