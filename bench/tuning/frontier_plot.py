"""The work-precision plot of a tuning: per knob, its accuracy figure against its cost figure
(the wire's knobs: shown error against download per player; the physics knobs: stack drift
against physics time per tick; the crowd's: arrival drift against AI time per tick; the gpu
knob: the device's float error against AI time per tick)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

AXES = {"shown_error_p99": ("shown error p99, m", 1), "kbps_per_client": ("download per player, kbit/s", 1),
        "stack_drift": ("stack drift, mm", 1000), "physics_ms": ("physics per tick, ms", 1),
        "arrival_drift": ("arrival drift p99, s", 1), "ai_ms": ("AI per tick, ms", 1),
        "path_overhead": ("path overhead max, %", 100), "planner_ms": ("planner per tick, ms", 1),
        "gpu_error": ("gpu error, mm", 1000)}


def plot(knobs, chosen, limits, together, title, path):
    """One panel per knob; `together` is the confirmed figures as text, for the title."""
    n = len(knobs)
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.8), squeeze=False)
    limit_of = {l.metric: l.most for l in limits}
    for ax, knob in zip(axes[0], knobs):
        (xlabel, xs_scale), (ylabel, ys_scale) = AXES[knob.cost], AXES[knob.accuracy]

        def at(f):
            return f[knob.cost] * xs_scale, f[knob.accuracy] * ys_scale

        if not knob.sweep:  # every value's run failed
            ax.set_title(f"{knob.name}: no run finished", fontsize=10)
            continue
        ax.plot(*zip(*(at(f) for _, f in sorted(knob.sweep, key=lambda vf: vf[1][knob.cost]))),
                "o-", color="tab:blue", zorder=2)
        for (value, f) in knob.sweep:
            ax.annotate(knob.label(value), at(f), textcoords="offset points", xytext=(4, 4), fontsize=8)
            if value == knob.scene_value:
                ax.plot(*at(f), "s", mfc="none", ms=11, color="grey", zorder=3, label="the scene's own")
            if value == chosen[knob.name]:
                ax.plot(*at(f), "o", ms=10, color="tab:red", zorder=4, label="chosen")
        if knob.accuracy in limit_of:
            ax.axhline(limit_of[knob.accuracy] * ys_scale, color="tab:red", ls="--", lw=1)
        if knob.cost in limit_of:
            ax.axvline(limit_of[knob.cost] * xs_scale, color="tab:orange", ls="--", lw=1)
        if knob.accuracy == "stack_drift" and max(f["stack_drift"] for _, f in knob.sweep) > 0:
            ax.set_yscale("symlog", linthresh=0.1)  # from a tenth of a mm to metres of collapse
            ax.set_ylim(bottom=0)
        ax.set_title(knob.name, fontsize=10)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{title}; all chosen together:\n{together}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
