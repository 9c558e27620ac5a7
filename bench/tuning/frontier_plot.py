"""The work-precision plot of a tuning: per knob, shown error against bandwidth per player."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot(knobs, chosen, limits, confirmed, title, path):
    n = len(knobs)
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.8), squeeze=False)
    error_limit = next((l.most for l in limits if l.metric == "shown_error_p99"), None)
    kbps_limit = next((l.most for l in limits if l.metric == "kbps_per_client"), None)
    for ax, knob in zip(axes[0], knobs):
        xs = [f["kbps_per_client"] for _, f in knob.sweep]
        ys = [f["shown_error_p99"] for _, f in knob.sweep]
        ax.plot(xs, ys, "o-", color="tab:blue", zorder=2)
        for (value, f) in knob.sweep:
            ax.annotate(knob.label(value), (f["kbps_per_client"], f["shown_error_p99"]),
                        textcoords="offset points", xytext=(4, 4), fontsize=8)
            if value == knob.scene_value:
                ax.plot(f["kbps_per_client"], f["shown_error_p99"], "s", mfc="none", ms=11,
                        color="grey", zorder=3, label="the scene's own")
            if value == chosen[knob.name]:
                ax.plot(f["kbps_per_client"], f["shown_error_p99"], "o", ms=10, color="tab:red",
                        zorder=4, label="chosen")
        if error_limit is not None:
            ax.axhline(error_limit, color="tab:red", ls="--", lw=1)
        if kbps_limit is not None:
            ax.axvline(kbps_limit, color="tab:orange", ls="--", lw=1)
        ax.set_title(knob.name, fontsize=10)
        ax.set_xlabel("download per player, kbit/s")
        ax.set_ylabel("shown error p99, m")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{title}; all chosen together: {confirmed['shown_error_p99']:.3f} m, "
                 f"{confirmed['kbps_per_client']:.1f} kbit/s", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
