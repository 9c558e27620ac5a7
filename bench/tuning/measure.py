"""One measured run: the scene with a candidate overlay on a local cluster (deploy/cluster.sh:
zone ranks, a gateway, a fleet of players), or on its zone ranks alone (mpirun, no DDS, no
players, as fast as they go, to a fixed tick: for the crowd's figures), read back as the
budget's figures."""
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "deploy"))
import truth_error  # noqa: E402  (deploy/truth_error.py)
from tuning import arrivals  # noqa: E402

CLUSTER_FILE = """# Written by bench/tune.py for one measured run.
[cluster]
scene = {scene}
duration = {seconds}
truth_every = {truth_every}
zone_args = --dump-state {end_state} --dump-state-at {end_tick}
record = no

[host local]
reach = local
zones = {ranks}

[gateway g1]
host = local

[fleet players]
host = local
players = {players}
"""


WARMUP_S = 2  # seconds of a run left out of its bandwidth
# A body of the reference run moving slower than this at its end rests there (the engine's
# sleep threshold, docs/physics.md): where it rests does not depend on the tick the run stopped.
REST_SPEED = 0.05
END_STATE = "end_state.jsonl"  # zone_node --dump-state: every entity at the end tick (below)
ARRIVALS = "arrivals.csv"  # zone_node --arrivals: the tick each flow-field NPC arrived
# Zones start this long at least before the players (gateway and fleet start-up), and run until
# the players are done: a run of S seconds of players reaches tick (S + LEAD_S) x rate.
LEAD_S = 2


class RunError(RuntimeError):
    pass


def end_tick(scene, seconds):
    """The tick a run of `seconds` of players compares its bodies at: every run of that length
    reaches it, and runs stopped on different ticks are compared on one."""
    tick = scene.get("tick", {}) or {}
    rate = float(tick.get("rate_hz") or 1 / float(tick.get("dt", 1 / 30)))
    return int(round((seconds + LEAD_S) * rate))


def ranks_of(scene):
    zones = scene.get("zones", {}) or {}
    return int(zones.get("columns", 1)) * int(zones.get("rows", 1))


def percentile(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, max(0, int(round(p / 100 * len(v) + 0.5)) - 1))] if v else float("nan")


def steady_kbps(run):
    """Download per player after the first WARMUP_S, when every view has spawned in (the first
    second carries each player's whole view, several times a steady second's bytes)."""
    seconds = [json.loads(l) for l in (run / "clients.jsonl").read_text().splitlines() if l.strip()]
    steady = [s for s in seconds if s["t"] > WARMUP_S + 0.5 and s["players"] > 0]
    if not steady:
        return None
    return sum(s["bytes_in_per_s"] / s["players"] for s in steady) / len(steady) * 8 / 1000


def end_bodies(run):
    """id -> (position, speed) of every rigid body at the end tick of a finished run."""
    if not (run / END_STATE).exists():
        raise RunError(f"{run}: the zones stopped before the end tick (no {END_STATE}; "
                       f"did they fall behind real time?)")
    bodies = {}
    for line in (run / END_STATE).read_text().splitlines():
        e = json.loads(line)
        if e.get("kind") == "rigid_body":
            bodies[e["id"]] = (e["pos"], math.hypot(*e["vel"]))
    return bodies


def resting(reference):
    """The bodies (id -> end position) that rest at the end of the reference run."""
    return {i: pos for i, (pos, speed) in reference.items() if speed < REST_SPEED}


def stack_drift(run, rest):
    """The largest distance any body resting at the end of the reference run (`rest`, from
    resting()) ends in this run from where the reference ends it, and which body."""
    here = end_bodies(run)
    missing = [i for i in rest if i not in here]
    if missing:
        raise RunError(f"{run}: {len(missing)} resting bodies of the reference are not in its end state")
    return max(((math.dist(here[i][0], pos), i) for i, pos in rest.items()), default=(0.0, None))


def physics_ms(run):
    """Mean physics phase time per tick, summed over the zone ranks (their summaries)."""
    zones = [json.loads(p.read_text()) for p in run.glob("zone_*_summary.json")]
    return sum(z["physics_ms_mean"] for z in zones)


def tick_seconds(scene):
    tick = scene.get("tick", {}) or {}
    return 1 / float(tick["rate_hz"]) if tick.get("rate_hz") else float(tick.get("dt", 1 / 30))


def zone_ticks(scene, seconds):
    """The ticks of a zone-only run of `seconds` of simulated time."""
    return int(round(seconds / tick_seconds(scene)))


def path_figures(zones, ticks):
    """The path planner's figures from the zone summaries of a run of `ticks` ticks: time in the
    planner per tick (summed over the ranks) and, with agents.paths.audit, the largest and the
    mean overhead over the A* optimum of the paths planned (0 when none was)."""
    audited = sum(z.get("paths_audited", 0) for z in zones)
    return {"planner_ms": sum(z.get("path_plan_ns", 0) for z in zones) / ticks / 1e6,
            "paths_audited": audited,
            "path_overhead": max((z.get("path_overhead_max_ppm", 0) for z in zones), default=0) / 1e6,
            "path_overhead_mean": sum(z.get("path_overhead_ppm", 0) for z in zones) / audited / 1e6 if audited else 0.0}


def run_arrivals(run):
    """id -> arrival tick of a finished zone-only run; RunError when its file is malformed."""
    try:
        return arrivals.read(run / ARRIVALS)
    except (OSError, arrivals.ArrivalsError) as e:
        raise RunError(str(e)) from None


def run_zones(overlay, folder, ranks, ticks, dt, bin_dir, reference=None):
    """Runs the overlay's scene on `ranks` zone ranks alone (no DDS, no players, as fast as
    they go) for `ticks` ticks of `dt` s; returns its figures: the slowest rank's p99 tick
    time, the physics and AI time per tick summed over the ranks (the AI time without the path
    audit's searches), the path planner's figures (path_figures), how many flow NPCs arrived,
    and against `reference` (a dict that may hold `arrivals`, id -> tick, `rest`, the bodies
    resting at the end of a reference run of the same length, and `end`, every entity's end
    position in it) the arrival drift, stack drift and gpu error. Raises RunError when a rank fails or the run stops short of `ticks` (naming
    the tick it reached)."""
    run = folder / "run"
    if run.exists():  # a repetition: the zones must not read an earlier run's files
        shutil.rmtree(run)
    run.mkdir(parents=True)
    cmd = ["mpirun", "-np", str(ranks), "--oversubscribe", "--bind-to", "none", str(bin_dir / "zone_node"),
           "--scene", str(overlay), "--ticks", str(ticks), "--no-dds", "--gpu", "scene", "--metrics", str(run),
           "--arrivals", str(run / ARRIVALS), "--dump-state", str(run / END_STATE)]
    with open(folder / "zones.log", "w") as out:
        p = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=ROOT)
    if p.returncode != 0:
        lines = (folder / "zones.log").read_text(errors="replace").strip().splitlines()
        # A rank's own error names the fault; mpirun's follow-on lines only say that it aborted.
        own = [l for l in lines if l.startswith("zone_node:")][:1]
        raise RunError(f"the zone run of {overlay} failed (exit {p.returncode}; {folder / 'zones.log'}):\n    "
                       + "\n    ".join(own or lines[-6:]))
    zones = [json.loads(s.read_text()) for s in sorted(run.glob("zone_*_summary.json"))]
    if len(zones) != ranks:
        raise RunError(f"{run}: {len(zones)} zone summaries, expected {ranks}")
    reached = min(z["ticks"] for z in zones)
    if reached < ticks or not (run / ARRIVALS).exists():
        raise RunError(f"{run}: the zones stopped at tick {reached} of {ticks}")
    f = {"tick_ms_p99": max(z["tick_ms_p99"] for z in zones),
         "physics_ms": sum(z["physics_ms_mean"] for z in zones),
         # agents.paths.audit's A* searches run inside the AI phase: left out, so that a path
         # budget's runs cost what the scene will.
         "ai_ms": sum(z["ai_ms_mean"] for z in zones) - sum(z.get("path_audit_ns", 0) for z in zones) / ticks / 1e6,
         "arrived": len(run_arrivals(run)),
         **path_figures(zones, ticks)}
    reference = reference or {}
    if "arrivals" in reference:
        f.update(arrivals.drift(run_arrivals(run), reference["arrivals"], ticks, dt))
    if reference.get("rest"):
        f["stack_drift"], f["stack_drift_body"] = stack_drift(run, reference["rest"])
        f["resting_bodies"] = len(reference["rest"])
    if "end" in reference:
        f["gpu_error"], f["gpu_error_entity"] = largest_departure(run, reference["end"])
        f["entities_compared"] = len(reference["end"])
    return f


def end_positions(run):
    """id -> position of every entity at the end of a finished zone-only run."""
    if not (run / END_STATE).exists():
        raise RunError(f"{run}: no {END_STATE}: the zones did not write their end state")
    return {e["id"]: e["pos"] for e in map(json.loads, (run / END_STATE).read_text().splitlines())}


def largest_departure(run, reference):
    """The largest distance between where this run ends an entity and where the reference run
    (`reference`, end_positions()) ends it, and which entity; RunError when the two runs do not
    end with the same entities."""
    here = end_positions(run)
    if here.keys() != reference.keys():
        raise RunError(f"{run}: {len(here.keys() ^ reference.keys())} entities are in only one of this run's "
                       "and the reference's end states")
    return max(((math.dist(here[i], pos), i) for i, pos in reference.items()), default=(0.0, None))


def figures_of(run, rest=None):
    """The budget's metrics (tuning/budget.py) from a finished run folder; stack_drift only
    with the resting bodies of a reference run."""
    report = json.loads((run / "report.json").read_text())
    clients = report["clients"]
    if not clients:
        raise RunError(f"{run}: no player finished the run")
    errors, _, _ = truth_error.join(run)
    shown = [e for per_order in errors.values() for e in per_order]
    if not shown:
        raise RunError(f"{run}: no shown sample met a truth sample (truth_every too sparse?)")
    f = {"shown_error_p99": percentile(shown, 99),
         "kbps_per_client": steady_kbps(run) or
         sum(c["bytes_in_per_s"] for c in clients) * 8 / 1000 / len(clients),
         "tick_ms_p99": max(z["tick_ms_p99"] for z in report["zones"]),
         "physics_ms": physics_ms(run),
         "ai_ms": sum(json.loads(p.read_text())["ai_ms_mean"] for p in run.glob("zone_*_summary.json")),
         "samples": len(shown)}
    if rest:
        f["stack_drift"], f["stack_drift_body"] = stack_drift(run, rest)
        f["resting_bodies"] = len(rest)
    return f


def run_once(overlay, folder, ranks, seconds, players, truth_every, bin_dir, tick, rest=None):
    """Runs the overlay's scene, its bodies written at `tick` (end_tick()); returns its figures
    (stack_drift against `rest`, the bodies resting at that tick of a reference run of the same
    length, when given). Raises RunError with the cluster's words, or when a zone stopped before
    `tick` (the tuner then skips the setting)."""
    folder.mkdir(parents=True, exist_ok=True)
    cluster = folder / "tune.cluster"
    run = folder / "run"
    cluster.write_text(CLUSTER_FILE.format(scene=overlay, seconds=seconds, truth_every=truth_every,
                                           ranks=ranks, players=players,
                                           end_state=shlex.quote(str(run / END_STATE)), end_tick=tick))
    env = dict(os.environ, ZONESIM_BIN=str(bin_dir))
    with open(folder / "cluster.log", "w") as out:
        p = subprocess.run(["bash", ROOT / "deploy" / "cluster.sh", cluster, run], stdout=out,
                           stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    if p.returncode != 0:
        tail = (folder / "cluster.log").read_text(errors="replace").strip().splitlines()[-6:]
        raise RunError(f"the run of {overlay} failed (exit {p.returncode}; {folder / 'cluster.log'}):\n    "
                       + "\n    ".join(tail))
    reached = [json.loads(z.read_text())["ticks"] for z in run.glob("zone_*_summary.json")]
    if not reached or min(reached) < tick:
        raise RunError(f"{run}: the zones stopped at tick {min(reached, default=0)}, before the end tick {tick} "
                       "(did they fall behind real time?)")
    return figures_of(run, rest)
