#!/usr/bin/python3
"""zonesim's tuner (issue 19): the cheapest settings of a scene that meet an error budget.

    /usr/bin/python3 bench/tune.py SCENE --budget 'shown_error_p99<=0.25,kbps_per_client<=150'

It runs the scene on a local cluster (zone ranks, a gateway, a fleet of players) once with the
scene's own settings, then once per candidate value of each knob the scene uses, knob after
knob (those already swept at their choices, the rest at the scene's values), and measures each
run: the error clients showed against the zones' truth, the download per player, the tick and
physics time, and in a scene with rigid bodies the stack drift: how far the bodies resting at
the end of a reference run (every physics knob at its most accurate, run first) end from where
it ends them. Per knob it picks the cheapest value (least download for the wire's knobs, least
physics time for the physics knobs; costs within --tie, or --time-tie for times, of each other
are noise, and the more accurate of them wins) whose run met every limit, and names the limit
that stopped a cheaper one. The
choices together are confirmed by a longer run; if that run breaks a limit, the knob value that
lowered that figure most in its sweep is taken and the run is repeated. It writes the result as an
overlay of the scene (docs/scene-format.md, "Overlay files") that every program's --scene
reads, a JSON of every run, and a work-precision plot per knob.

A budget that limits the crowd (arrival_drift, arrival_drift_mean) is measured on runs of the
zone ranks alone, without players, as fast as they go: the scene's flow-field NPCs arrive at
their destinations, and each run's arrival ticks (zone_node --arrivals) are compared with a
reference run's, the level of detail off (lod.enabled: false); its knobs are the lod section's
periods, steering, crowding and bands, and last whether it is on at all, judged by AI time per
tick. A budget that limits path_overhead is measured the same way, with agents.paths.audit on:
every plan of the scene's agents is also planned by A*, and the largest excess over that
optimum is the figure; its knobs are the planner (map.navigation), landmarks and the HPA*
cluster size, judged by AI time per tick (planning and following paths; the audit's own
searches left out). A budget that limits gpu_error is measured the same way, on a scene with
flocks: each run's end state against a reference run with everything on the CPU (gpu.mode off,
double); its knob is gpu.mode (off, on, and the scene's own, auto by default), judged by AI time
per tick. Zone-only runs of other knobs keep everything on the CPU.

A sweep run that fails or stops short of its end tick is reported and its value skipped; the
sweep goes on. A budget no measured setting meets is refused (exit 2), naming the limit and
the best reached; a choice the confirmation cannot hold fails with exit 3. Nothing is written
in either case.
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
    p.add_argument("--time-tie", type=float, default=0.25,
                   help="physics times this close (a fraction) count as equal (default 0.25: times on a "
                        "shared machine vary by 20 %% from run to run)")
    p.add_argument("--repeat", type=int, default=3,
                   help="runs of each setting where runs are of the zones alone (crowd, path budgets): the least "
                        "time of them counts (default 3)")
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
    if a.players < 1 or a.truth_every < 1 or a.repeat < 1:
        p.error("--players, --truth-every and --repeat must be at least 1")
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
    def __init__(self, args, scene, zones_only=False, audit_paths=False):
        self.a = args
        self.ranks = measure.ranks_of(scene)
        self.runs = []  # every measured run, for the JSON
        self.count = 0
        self.scene = scene
        self.zones_only = zones_only  # crowd and path budgets: the zones alone, no players
        self.audit_paths = audit_paths  # path budgets: every plan against the A* optimum
        self.refs = {}  # run length -> what its reference run left: resting bodies, arrivals

    def measure(self, settings, label, seconds):
        """Runs the scene with these dotted-key settings; returns its figures. Raises
        measure.RunError (the run is counted and kept in the JSON as failed) when it fails or
        stops short."""
        self.count += 1
        folder = self.a.work / f"run-{self.count:02d}"
        folder.mkdir(parents=True, exist_ok=True)
        overlay = folder / "candidate.yaml"
        if self.audit_paths:  # a measurement: changes no path, costs an A* search per plan
            settings = {**settings, "agents.paths.audit": True}
        if self.zones_only:  # on the CPU unless the gpu knob says otherwise: runs repeat exactly
            settings = {**knob_defs.GPU_REFERENCE, **settings}
        overlay.write_text(knob_defs.overlay_text(self.a.scene, settings, [f"tune candidate: {label}"]))
        started = time.monotonic()
        ref = self.refs.get(seconds, {})
        try:
            if self.zones_only:
                f = self.zone_runs(overlay, folder, seconds, ref)
            else:
                f = measure.run_once(overlay, folder, self.ranks, seconds, self.a.players, self.a.truth_every,
                                     self.a.bin, measure.end_tick(self.scene, seconds), ref.get("rest"))
        except measure.RunError as e:
            print(f"  [{self.count:2d}] {label:<40} failed, skipped: {e}", flush=True)
            self.runs.append({"label": label, "settings": settings, "seconds": seconds, "failed": str(e)})
            raise
        print(f"  [{self.count:2d}] {label:<40} {figures_line(f)}  ({time.monotonic() - started:.0f} s)", flush=True)
        self.runs.append({"label": label, "settings": settings, "seconds": seconds, "figures": f})
        return f

    def zone_runs(self, overlay, folder, seconds, ref):
        """--repeat zone-only runs of one setting (the last one's files stay in folder/run):
        their times are the least measured, the figure of a run least disturbed by other load
        on the machine; their errors, which a run without players repeats exactly, the largest."""
        runs = [measure.run_zones(overlay, folder, self.ranks, measure.zone_ticks(self.scene, seconds),
                                  measure.tick_seconds(self.scene), self.a.bin, ref) for _ in range(self.a.repeat)]
        f = dict(runs[0])
        for key in f:
            pick = min if key.endswith("_ms") or key.startswith("tick_ms") else max
            f[key] = pick(r[key] for r in runs)
        return f

    def reference(self, settings, seconds, bodies, crowd, gpu=False):
        """Runs the reference (every physics knob at its most accurate, the crowd level of detail
        off, everything on the CPU) for `seconds` and keeps what later runs of that length are
        compared with: the bodies resting at its end tick (stack_drift), every flow NPC's arrival
        tick (arrival_drift) and every entity's end position (gpu_error). Returns how many bodies
        rest and how many NPCs arrived."""
        what = " and ".join(w for w, on in (("physics", bodies), ("crowds", crowd), ("offload", gpu)) if on)
        self.measure(settings, f"reference: {what} at their most accurate", seconds)
        run = self.a.work / f"run-{self.count:02d}" / "run"
        ref = {}
        if bodies:
            ref["rest"] = measure.resting(measure.end_bodies(run))
            self.runs[-1]["resting_bodies"] = len(ref["rest"])
            tick = measure.zone_ticks(self.scene, seconds) if self.zones_only else measure.end_tick(self.scene, seconds)
            print(f"       {len(ref['rest'])} bodies rest at tick {tick} of the reference: stack_drift is "
                  "measured on them", flush=True)
        if crowd:
            ref["arrivals"] = measure.run_arrivals(run)
            self.runs[-1]["arrived"] = len(ref["arrivals"])
            print(f"       {len(ref['arrivals'])} flow NPCs arrive within the reference's "
                  f"{measure.zone_ticks(self.scene, seconds)} ticks: arrival_drift is measured against them",
                  flush=True)
        if gpu:
            ref["end"] = measure.end_positions(run)
            print(f"       {len(ref['end'])} entities end the reference on the CPU: gpu_error is measured "
                  "against them", flush=True)
        self.refs[seconds] = ref
        return len(ref.get("rest", {})), len(ref.get("arrivals", {}))


def figures_line(f):
    """One run's figures, as the sweep prints them."""
    parts = []
    if "shown_error_p99" in f:
        parts.append(f"error p99 {f['shown_error_p99']:7.3f} m  {f['kbps_per_client']:7.1f} kbit/s")
    parts.append(f"tick p99 {f['tick_ms_p99']:6.2f} ms  physics {f['physics_ms']:6.3f} ms")
    if "ai_ms" in f:
        parts.append(f"ai {f['ai_ms']:6.3f} ms")
    if "stack_drift" in f:
        parts.append(f"stack drift {f['stack_drift'] * 1000:8.2f} mm")
    if "arrival_drift" in f:
        parts.append(f"arrival drift p99 {f['arrival_drift']:5.2f} s mean {f['arrival_drift_mean']:5.2f} s "
                     f"({f['arrived']} arrived)")
    if "gpu_error" in f:
        parts.append(f"gpu error {f['gpu_error'] * 1000:9.4f} mm")
    if f.get("paths_audited"):
        parts.append(f"planner {f['planner_ms']:7.4f} ms  path overhead max {f['path_overhead'] * 100:6.3f} % "
                     f"mean {f['path_overhead_mean'] * 100:6.4f} % ({f['paths_audited']} paths)")
    return "  ".join(parts)


def settings_of(knobs, values):
    return {key: v for k in knobs for key, v in zip(k.keys, values[k.name])}


def choose(knob, limits, tie):
    """The cheapest value whose run met every limit (or None), and why nothing cheaper was.
    Costs (the knob's cost figure) within `tie` (a fraction) of the cheapest are run-to-run
    noise, not savings: among those the most accurate (its accuracy figure) wins."""
    fine = [(v, f) for v, f in knob.sweep if not budget.broken(limits, f) and v not in knob.unsettled]
    if not fine:
        return None, "no value met every limit: kept the scene's"
    least = min(f[knob.cost] for _, f in fine)
    level = [(v, f) for v, f in fine if f[knob.cost] <= least * (1 + tie)]
    value, f = min(level, key=lambda vf: (vf[1][knob.accuracy], vf[1][knob.cost], vf[1]["tick_ms_p99"]))
    cheaper = [(v, g) for v, g in knob.sweep if g[knob.cost] < least * (1 - tie)]
    why = f"the most accurate within {tie * 100:g} % of the least {knob.cost} that met the budget"
    held = sorted({l.describe() for _, g in cheaper for l in budget.broken(limits, g)})
    unsettled = [knob.label(v) for v, _ in knob.sweep if v in knob.unsettled]
    return value, why + ("; cheaper values broke " + "; ".join(held) if held else "") + \
        (f"; {', '.join(unsettled)} measured, not chosen: it decides at start-up by the load" if unsettled else "")


def refuse_if_impossible(limits, knobs, baseline):
    """Exit 2 naming each limit that no measured run met."""
    points = ([("the scene's own settings", baseline)] if baseline else []) + \
        [(f"{k.name} = {k.label(v)}", f) for k in knobs for v, f in k.sweep]
    if not points:
        print("refused: no run of the sweep finished (see the failures above)", file=sys.stderr)
        sys.exit(2)
    unmet = [l for l in limits if not any(l.met(f) for _, f in points)]
    for l in unmet:
        where, f = min(points, key=lambda p: p[1][l.metric])
        print(f"refused: no setting meets {l.describe()}: the best measured is "
              f"{f[l.metric]:.4g} {budget.METRICS[l.metric][0]} ({where})", file=sys.stderr)
    if unmet:
        sys.exit(2)


def tie_of(knob, a):
    return a.time_tie if knob.cost.endswith("_ms") else a.tie


def print_frontier(knobs, chosen, reasons, limits):
    print("\nfrontier (each knob in turn, those before it at their choices, the rest at the scene's):")
    shown = [m for m in ("shown_error_p99", "kbps_per_client", "tick_ms_p99", "physics_ms", "stack_drift",
                         "ai_ms", "arrival_drift", "arrival_drift_mean", "planner_ms", "path_overhead",
                         "path_overhead_mean", "gpu_error")
             if any(m in f for k in knobs for _, f in k.sweep)
             and (not m.startswith(("planner", "path")) or any(f.get("paths_audited") for k in knobs for _, f in k.sweep))]
    print(f"  {'knob':<22} {'value':<16} " + " ".join(f"{m:>15}" for m in shown))
    for k in knobs:
        for v, f in sorted(k.sweep, key=lambda vf: -vf[1][k.cost]):
            mark = ("chosen" if v == chosen[k.name] else "") + (" (scene's)" if v == k.scene_value else "")
            bad = ", ".join(l.metric for l in budget.broken(limits, f))
            print(f"  {k.name:<22} {k.label(v):<16} " + " ".join(f"{f[m]:>15.4g}" for m in shown) +
                  f"  {mark}{'  breaks ' + bad if bad else ''}")
        for v, why in k.failed:
            print(f"  {k.name:<22} {k.label(v):<16} failed, skipped: {why.splitlines()[-1].strip()}")
        print(f"  {'':<22} -> {k.label(chosen[k.name])}: {reasons[k.name]}")


def figures_text(f):
    """The confirmed figures, as the overlay's header and the last line print them."""
    parts = []
    if "shown_error_p99" in f:
        parts.append(f"error p99 {f['shown_error_p99']:.3f} m, {f['kbps_per_client']:.1f} kbit/s per player")
    parts.append(f"tick p99 {f['tick_ms_p99']:.2f} ms, physics {f['physics_ms']:.3f} ms")
    if "ai_ms" in f:
        parts.append(f"ai {f['ai_ms']:.4f} ms")
    if "stack_drift" in f:
        parts.append(f"stack drift {f['stack_drift'] * 1000:.2f} mm over {f['resting_bodies']} resting bodies")
    if "arrival_drift" in f:
        parts.append(f"arrival drift p99 {f['arrival_drift']:.2f} s, mean {f['arrival_drift_mean']:.3f} s, "
                     f"max {f['arrival_drift_max']:.2f} s over {f['arrivals_compared']} NPCs "
                     f"({f['arrived']} arrived)")
    if "gpu_error" in f:
        parts.append(f"gpu error {f['gpu_error'] * 1000:.4f} mm over {f['entities_compared']} entities")
    if f.get("paths_audited"):
        parts.append(f"planner {f['planner_ms']:.4f} ms, path overhead max {f['path_overhead'] * 100:.3f} %, "
                     f"mean {f['path_overhead_mean'] * 100:.4f} % over {f['paths_audited']} paths")
    return ", ".join(parts)


def sweep(t, knobs, chosen, limits, a):
    """Coordinate descent: each knob is swept with the knobs before it at their choices, so a
    scene whose own settings break the budget still gets its later knobs judged. A run that
    fails or stops short is reported and its value skipped; the sweep goes on. Fills each
    knob's sweep and failures and `chosen`; returns the reasons per knob and the scene's own
    settings' figures (None when that run failed)."""
    reasons = {}
    try:
        here = t.measure(settings_of(knobs, chosen), "the scene's own settings", a.seconds)
    except measure.RunError as e:
        here, here_failed = None, str(e)
    baseline = here
    for k in knobs:
        for v in k.values:
            if v == chosen[k.name] and here is None:
                k.failed.append((v, here_failed))
                continue
            if v == chosen[k.name]:
                k.sweep.append((v, here))
                continue
            try:
                k.sweep.append((v, t.measure(settings_of(knobs, {**chosen, k.name: v}),
                                             f"{k.name} = {k.label(v)}", a.seconds)))
            except measure.RunError as e:
                k.failed.append((v, str(e)))
        value, reasons[k.name] = choose(k, limits, tie_of(k, a))
        if value is not None:
            chosen[k.name] = value
        measured = dict(k.sweep)
        if chosen[k.name] in measured:
            here = measured[chosen[k.name]]
        else:
            here_failed = f"the run of {k.name} = {k.label(chosen[k.name])} failed"
            here = None
    return reasons, baseline


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
    limited = {l.metric for l in a.limits}
    crowd_limits = sorted(limited & set(budget.CROWD_METRICS))
    path_limits = sorted(limited & set(budget.PATH_METRICS))
    gpu_limits = sorted(limited & set(budget.GPU_METRICS))
    zones_only = bool(crowd_limits or path_limits or gpu_limits)
    uses = knob_defs.scene_uses(scene)
    if zones_only:
        players = sorted(limited & set(budget.PLAYER_METRICS))
        if players:
            print(f"refused: {', '.join(crowd_limits + path_limits + gpu_limits)} is measured on runs of the zones alone "
                  f"and {', '.join(players)} needs players: tune them in two runs of the tuner", file=sys.stderr)
            sys.exit(2)
        if crowd_limits and not uses["flow"]:
            print(f"refused: {', '.join(crowd_limits)} needs a flow-field crowd (populations[].flow), and "
                  f"{a.scene.name} has none", file=sys.stderr)
            sys.exit(2)
        if path_limits and not uses["paths"]:
            print(f"refused: {', '.join(path_limits)} needs agents that plan paths on a map (a type with "
                  f"navigate: true, and map:), and {a.scene.name} has none", file=sys.stderr)
            sys.exit(2)
        if gpu_limits and not uses["flock"]:
            print(f"refused: {', '.join(gpu_limits)} needs a flocking population (populations[].flock), the "
                  f"one workload a scene's knob moves to the device, and {a.scene.name} has none", file=sys.stderr)
            sys.exit(2)

    def unmeasured(k):
        """Why this budget's runs cannot judge knob k, or None."""
        if k.accuracy in budget.CROWD_METRICS and not crowd_limits:
            return "trades against arrival_drift, which only a budget that limits it measures"
        if k.accuracy in budget.PATH_METRICS and not path_limits:
            return "trades against path_overhead, which only a budget that limits it measures"
        if k.accuracy in budget.GPU_METRICS and not gpu_limits:
            return "trades against gpu_error, which only a budget that limits it measures"
        if zones_only and k.cost in budget.PLAYER_METRICS:
            return "needs players, and a crowd or path budget runs the zones alone"
        return None

    dropped = [(k.name, unmeasured(k)) for k in knobs if unmeasured(k)]
    if a.knobs and dropped:
        sys.exit("tune.py: --knobs: " + "; ".join(f"{name} {why}" for name, why in dropped))
    knobs = [k for k in knobs if not unmeasured(k)]
    if not knobs:
        print(f"refused: no knob of {a.scene.name} is judged by this budget (the crowd's level of detail "
              "needs the scene's lod section)", file=sys.stderr)
        sys.exit(2)
    physics = [k for k in knobs if k.accuracy == "stack_drift"]
    wants_drift = bool(physics) or any(l.metric in budget.PHYSICS_METRICS for l in a.limits)
    if wants_drift and not knob_defs.scene_uses(scene)["rigid_body"]:
        print(f"refused: {', '.join(budget.PHYSICS_METRICS)} needs rigid bodies, and "
              f"{a.scene.name} has none", file=sys.stderr)
        sys.exit(2)
    wants_crowd = bool(crowd_limits)
    wants_gpu = bool(gpu_limits)
    wants_reference = wants_drift or wants_crowd or wants_gpu
    a.work.mkdir(parents=True, exist_ok=True)
    runs = 1 + wants_reference + sum(len(k.values) - 1 for k in knobs)
    how = "the zones alone, as fast as they go" if zones_only else f"{a.players} players"
    print(f"tuning {a.scene.name} against {', '.join(l.describe() for l in a.limits)}: "
          f"{len(knobs)} knobs, {runs} runs of {a.seconds:g} s and "
          f"{1 + (wants_reference and a.confirm_seconds != a.seconds)} of {a.confirm_seconds:g} s, "
          f"{how}, {measure.ranks_of(scene)} zone ranks; runs in {a.work}")
    t = Tuner(a, scene, zones_only, bool(path_limits))
    chosen = {k.name: k.scene_value for k in knobs}
    reference_knobs = knob_defs.physics_knobs(scene) if wants_drift else []
    reference_knobs += knob_defs.crowd_knobs(scene) if wants_crowd else []
    reference_knobs += [knob_defs.gpu_knob(scene)] if wants_gpu else []

    def reference_run(seconds):
        reference = {**settings_of(knobs, chosen), **knob_defs.reference_settings(reference_knobs)}
        try:
            rest, arrived = t.reference(reference, seconds, wants_drift, wants_crowd, wants_gpu)
        except measure.RunError as e:
            sys.exit(f"tune.py: the reference run failed, so nothing can be compared with it: {e}")
        if wants_drift and not rest:
            print("refused: no body rests at the end of the reference run, so stack_drift measures "
                  "nothing here", file=sys.stderr)
            sys.exit(2)
        if wants_crowd and not arrived:
            print(f"refused: no flow NPC arrives within the reference run's {seconds:g} s, so "
                  "arrival_drift measures nothing here (lengthen --seconds)", file=sys.stderr)
            sys.exit(2)

    if wants_reference:
        reference_run(a.seconds)
    reasons, baseline = sweep(t, knobs, chosen, a.limits, a)
    refuse_if_impossible(a.limits, knobs, baseline)
    print_frontier(knobs, chosen, reasons, a.limits)

    # The choices were measured in short runs; a full-length run of them must hold too.
    for attempt in range(4):
        if wants_reference and a.confirm_seconds not in t.refs:  # the full-length run's own reference
            reference_run(a.confirm_seconds)
        try:
            confirmed = t.measure(settings_of(knobs, chosen), "all chosen together", a.confirm_seconds)
        except measure.RunError as e:
            sys.exit(f"tune.py: the confirming run failed, nothing written: {e}")
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
              f"confirmed over {a.confirm_seconds:g} s with "
              f"{'the zones alone' if zones_only else f'{a.players} players'}: {figures_text(confirmed)}",
              f"the binding limit: {binds.describe()} ({binds.slack(confirmed) * 100:.0f} % left)"]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    base = Path(os.path.relpath(a.scene, a.out.parent))
    a.out.write_text(knob_defs.overlay_text(base, settings_of(knobs, chosen), header))
    (a.work / "tune.json").write_text(json.dumps({
        "scene": str(a.scene), "budget": [l.describe() for l in a.limits],
        "chosen": {k.name: k.label(chosen[k.name]) for k in knobs}, "reasons": reasons,
        "failed": {k.name: [k.label(v) for v, _ in k.failed] for k in knobs if k.failed},
        "confirmed": confirmed, "binding": binds.describe(), "runs": t.runs}, indent=2))
    try:
        from tuning import frontier_plot
        frontier_plot.plot(knobs, chosen, a.limits, figures_text(confirmed), f"{a.scene.name} tuned",
                           a.work / "frontier.png")
        plot_note = f", plot {a.work / 'frontier.png'}"
    except ImportError:
        plot_note = " (no matplotlib: no plot)"
    print(f"\nconfirmed over {a.confirm_seconds:g} s: {figures_text(confirmed)}; binding limit {binds.describe()}")
    print(f"overlay {a.out}{plot_note}, every run in {a.work / 'tune.json'}")


if __name__ == "__main__":
    main(sys.argv[1:])
