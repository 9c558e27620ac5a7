"""The plot of one knob's sweep (bench/knob_sweep.py): error shown to players, and how much of
the world they were shown, against the download per player.

    /usr/bin/python3 bench/tuning/sweep_plot.py SWEEP.csv OUT.png [TITLE]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot(rows, title, path):
    rows = sorted(rows, key=lambda r: float(r["kbps_per_client"]))
    kbps = [float(r["kbps_per_client"]) for r in rows]
    fig, (err, shown) = plt.subplots(1, 2, figsize=(10, 4))
    for metric, style, label in (("shown_error_p99", "o-", "all shown samples"),
                                 ("near_error_p99", "s--", "within 25 m of the player")):
        err.plot(kbps, [float(r[metric]) for r in rows], style, label=label)
    shown.plot(kbps, [int(r["samples"]) for r in rows], "o-", color="tab:green")
    for ax in (err, shown):
        for r, x in zip(rows, kbps):
            y = float(r["shown_error_p99"]) if ax is err else int(r["samples"])
            ax.annotate(str(r["value"]), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=8)
        ax.set_xlabel("download per player, kbit/s")
        ax.grid(alpha=0.3)
    err.set_ylabel("error shown to players, p99, m")
    err.legend(fontsize=8)
    shown.set_ylabel("entity samples shown (every K-th id)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: sweep_plot.py SWEEP.csv OUT.png [TITLE]")
    with open(sys.argv[1]) as f:
        plot(list(csv.DictReader(f)), sys.argv[3] if len(sys.argv) > 3 else sys.argv[1], sys.argv[2])
