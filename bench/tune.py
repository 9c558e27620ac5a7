#!/usr/bin/python3
"""zonesim's tuner (issue 19): the cheapest settings of a scene that meet an error budget.

    /usr/bin/python3 bench/tune.py SCENE --budget 'shown_error_p99<=0.25,kbps_per_client<=150'

It runs the scene on a local cluster (zone ranks, a gateway, a fleet of players) once with the
scene's own settings, then once per candidate value of each knob the scene uses, knob after
knob (those already swept at their choices, the rest at the scene's values), and measures each
run: the error clients showed against the zones' truth,
the download per player and the tick time. Per knob it picks the cheapest value (least download,
then tick time; downloads within --tie of each other are noise, and the more accurate of them
wins) whose run met every limit, and names the limit that stopped a cheaper one. The
choices together are confirmed by a longer run; if that run breaks a limit, the knob value that
lowered that figure most in its sweep is taken and the run is repeated. It writes the result as an
overlay of the scene (docs/scene-format.md, "Overlay files") that every program's --scene
reads, a JSON of every run, and a work-precision plot per knob.

A budget no measured setting meets is refused (exit 2), naming the limit and the best reached;
a choice the confirmation cannot hold fails with exit 3. Nothing is written in either case.
"""
import argparse
import json
import os
import shlex
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from tuning import budget, knobs as knob_defs, measure  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", type=Path, help="the scene file to tune")
    p.add_argument("--budget", required=True, help="limits, e.g. 'shown_error_p99<=0.25,kbps_per_client<=150' "
                   f"(known: {', '.join(budget.METRICS)})")
    p.add_argument("--out", type=Path, help="the overlay to write (default WORK/SCENE.tuned.yaml)")
    p.add_argument("--work", type=Path, help="where the runs go (default runs/tune-SCENE)")
    p.add_argument("--seconds", type=float, default=10, help="players' time per sweep run (default 10)")
    p.add_argument("--confirm-seconds", type=float, default=30, help="players' time of the confirming run")
    p.add_argument("--players", type=int, default=16)
    p.add_argument("--truth-every", type=int, default=8, help="sample every K-th entity id for the error")
    p.add_argument("--tie", type=float, default=0.03,
                   help="downloads this close (a fraction) count as equal: the more accurate wins (default 0.03)")
    p.add_argument("--knobs", help="only these knobs (comma-separated names as printed), default all")
    p.add_argument("--bin", type=Path, default=ROOT / "build" / "bin", help="the built programs")
    a = p.parse_args(argv)
    if not a.scene.is_file():
        p.error(f"scene {a.scene}: no such file")
    if not (a.bin / "zone_node").is_file():
        p.error(f"--bin {a.bin}: no zone_node there (build first: ninja -C build)")
    for name in ("seconds", "confirm_seconds"):
        if not getattr(a, name) >= 1:
            p.error(f"--{name.replace('_', '-')} must be at least 1")
    if a.players < 1 or a.truth_every < 1:
        p.error("--players and --truth-every must be at least 1")
    try:
        a.limits = budget.parse(a.budget)
    except budget.BudgetError as e:
        p.error(str(e))
    a.scene = a.scene.resolve()
    stem = a.scene.name.removesuffix(".yaml")
    a.work = (a.work or ROOT / "runs" / f"tune-{stem}").resolve()
    a.out = (a.out or a.work / f"{stem}.tuned.yaml").resolve()
    return a


class Tuner:
    def __init__(self, args, scene):
        self.a = args
        self.ranks = measure.ranks_of(scene)
        self.runs = []  # every measured run, for the JSON
        self.count = 0

    def measure(self, settings, label, seconds):
        """Runs the scene with these dotted-key settings; returns its figures."""
        self.count += 1
        folder = self.a.work / f"run-{self.count:02d}"
        folder.mkdir(parents=True, exist_ok=True)
        overlay = folder / "candidate.yaml"
        overlay.write_text(knob_defs.overlay_text(self.a.scene, settings, [f"tune candidate: {label}"]))
        started = time.monotonic()
        f = measure.run_once(overlay, folder, self.ranks, seconds, self.a.players, self.a.truth_every,
                             self.a.bin)
        print(f"  [{self.count:2d}] {label:<40} error p99 {f['shown_error_p99']:7.3f} m  "
              f"{f['kbps_per_client']:7.1f} kbit/s  tick p99 {f['tick_ms_p99']:6.2f} ms  "
              f"({time.monotonic() - started:.0f} s)", flush=True)
        self.runs.append({"label": label, "settings": settings, "seconds": seconds, "figures": f})
        return f


def settings_of(knobs, values):
    return {key: v for k in knobs for key, v in zip(k.keys, values[k.name])}


def cost(f):
    return (f["kbps_per_client"], f["tick_ms_p99"])


def choose(knob, limits, tie):
    """The cheapest value whose run met every limit (or None), and why nothing cheaper was.
    Downloads within `tie` (a fraction) of the cheapest are run-to-run noise, not savings:
    among those the most accurate wins."""
    fine = [(v, f) for v, f in knob.sweep if not budget.broken(limits, f)]
    if not fine:
        return None, "no value met every limit: kept the scene's"
    least = min(f["kbps_per_client"] for _, f in fine)
    level = [(v, f) for v, f in fine if f["kbps_per_client"] <= least * (1 + tie)]
    value, f = min(level, key=lambda vf: (vf[1]["shown_error_p99"], cost(vf[1])))
    cheaper = [(v, g) for v, g in knob.sweep if g["kbps_per_client"] < least * (1 - tie)]
    why = f"the most accurate within {tie * 100:g} % of the least download that met the budget"
    held = sorted({l.describe() for _, g in cheaper for l in budget.broken(limits, g)})
    return value, why + ("; cheaper values broke " + "; ".join(held) if held else "")


def refuse_if_impossible(limits, knobs, baseline):
    """Exit 2 naming each limit that no measured run met."""
    points = [("the scene's own settings", baseline)] + \
        [(f"{k.name} = {k.label(v)}", f) for k in knobs for v, f in k.sweep]
    unmet = [l for l in limits if not any(l.met(f) for _, f in points)]
    for l in unmet:
        where, f = min(points, key=lambda p: p[1][l.metric])
        print(f"refused: no setting meets {l.describe()}: the best measured is "
              f"{f[l.metric]:.4g} {budget.METRICS[l.metric][0]} ({where})", file=sys.stderr)
    if unmet:
        sys.exit(2)


def print_frontier(knobs, chosen, reasons, limits):
    print("\nfrontier (each knob in turn, those before it at their choices, the rest at the scene's):")
    print(f"  {'knob':<22} {'value':<16} {'error p99 m':>11} {'kbit/s':>8} {'tick p99 ms':>11}  ")
    for k in knobs:
        for v, f in sorted(k.sweep, key=lambda vf: -vf[1]["kbps_per_client"]):
            mark = ("chosen" if v == chosen[k.name] else "") + (" (scene's)" if v == k.scene_value else "")
            bad = ", ".join(l.metric for l in budget.broken(limits, f))
            print(f"  {k.name:<22} {k.label(v):<16} {f['shown_error_p99']:>11.3f} {f['kbps_per_client']:>8.1f} "
                  f"{f['tick_ms_p99']:>11.2f}  {mark}{'  breaks ' + bad if bad else ''}")
        print(f"  {'':<22} -> {k.label(chosen[k.name])}: {reasons[k.name]}")


def main(argv):
    a = parse_args(argv)
    scene = knob_defs.merged_scene(a.scene)
    knobs = knob_defs.knobs_for(scene)
    if a.knobs:
        wanted = [w.strip() for w in a.knobs.split(",")]
        unknown = [w for w in wanted if w not in [k.name for k in knobs]]
        if unknown:
            sys.exit(f"tune.py: --knobs: {', '.join(unknown)} not among this scene's "
                     f"({', '.join(k.name for k in knobs)})")
        knobs = [k for k in knobs if k.name in wanted]
    a.work.mkdir(parents=True, exist_ok=True)
    runs = 1 + sum(len(k.values) - 1 for k in knobs)
    print(f"tuning {a.scene.name} against {', '.join(l.describe() for l in a.limits)}: "
          f"{len(knobs)} knobs, {runs} runs of {a.seconds:g} s and one of {a.confirm_seconds:g} s, "
          f"{a.players} players, {measure.ranks_of(scene)} zone ranks; runs in {a.work}")
    t = Tuner(a, scene)
    chosen = {k.name: k.scene_value for k in knobs}
    reasons = {}
    try:
        # Coordinate descent: each knob is swept with the knobs before it at their choices, so
        # a scene whose own settings break the budget still gets its later knobs judged.
        here = t.measure(settings_of(knobs, chosen), "the scene's own settings", a.seconds)
        baseline = here
        for k in knobs:
            for v in k.values:
                f = here if v == chosen[k.name] else \
                    t.measure(settings_of(knobs, {**chosen, k.name: v}), f"{k.name} = {k.label(v)}", a.seconds)
                k.sweep.append((v, f))
            value, reasons[k.name] = choose(k, a.limits, a.tie)
            if value is not None:
                chosen[k.name] = value
            here = dict(k.sweep)[chosen[k.name]]
    except measure.RunError as e:
        sys.exit(f"tune.py: {e}")
    refuse_if_impossible(a.limits, knobs, baseline)
    print_frontier(knobs, chosen, reasons, a.limits)

    # The choices were measured in short runs; a full-length run of them must hold too.
    for attempt in range(4):
        try:
            confirmed = t.measure(settings_of(knobs, chosen), "all chosen together", a.confirm_seconds)
        except measure.RunError as e:
            sys.exit(f"tune.py: {e}")
        broken = budget.broken(a.limits, confirmed)
        if not broken:
            break
        limit = broken[0]
        # The knob value that lowered this figure most in its sweep, relative to the choice.
        gains = [(dict(k.sweep)[chosen[k.name]][limit.metric] - f[limit.metric], k, v)
                 for k in knobs for v, f in k.sweep if v != chosen[k.name]]
        gains = [g for g in gains if g[0] > 0]
        if not gains or attempt == 3:
            sys.exit(f"tune.py: the chosen settings together break {limit.describe()}: "
                     f"{confirmed[limit.metric]:.4g} {budget.METRICS[limit.metric][0]} over "
                     f"{a.confirm_seconds:g} s, and no knob's sweep lowers it further; nothing written")
        _, k, back = max(gains, key=lambda g: g[0])
        print(f"  the full-length run breaks {limit.describe()} ({confirmed[limit.metric]:.4g}): "
              f"{k.name} goes to {k.label(back)}")
        chosen[k.name] = back

    binds = budget.binding(a.limits, confirmed)
    header = [f"Written by bench/tune.py on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}:",
              f"  /usr/bin/python3 bench/tune.py {shlex.join(argv)}",
              "budget: " + ", ".join(l.describe() for l in a.limits),
              f"confirmed over {a.confirm_seconds:g} s with {a.players} players: error p99 "
              f"{confirmed['shown_error_p99']:.3f} m, {confirmed['kbps_per_client']:.1f} kbit/s per player, "
              f"tick p99 {confirmed['tick_ms_p99']:.2f} ms",
              f"the binding limit: {binds.describe()} ({binds.slack(confirmed) * 100:.0f} % left)"]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    base = Path(os.path.relpath(a.scene, a.out.parent))
    a.out.write_text(knob_defs.overlay_text(base, settings_of(knobs, chosen), header))
    (a.work / "tune.json").write_text(json.dumps({
        "scene": str(a.scene), "budget": [l.describe() for l in a.limits],
        "chosen": {k.name: k.label(chosen[k.name]) for k in knobs}, "reasons": reasons,
        "confirmed": confirmed, "binding": binds.describe(), "runs": t.runs}, indent=2))
    try:
        from tuning import frontier_plot
        frontier_plot.plot(knobs, chosen, a.limits, confirmed, f"{a.scene.name} tuned",
                           a.work / "frontier.png")
        plot_note = f", plot {a.work / 'frontier.png'}"
    except ImportError:
        plot_note = " (no matplotlib: no plot)"
    print(f"\nconfirmed over {a.confirm_seconds:g} s: error p99 {confirmed['shown_error_p99']:.3f} m, "
          f"{confirmed['kbps_per_client']:.1f} kbit/s per player, tick p99 {confirmed['tick_ms_p99']:.2f} ms; "
          f"binding limit {binds.describe()}")
    print(f"overlay {a.out}{plot_note}, every run in {a.work / 'tune.json'}")


if __name__ == "__main__":
    main(sys.argv[1:])
