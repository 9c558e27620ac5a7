"""One measured run: the scene with a candidate overlay on a local cluster (deploy/cluster.sh:
zone ranks, a gateway, a fleet of players), read back as the budget's figures."""
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "deploy"))
import truth_error  # noqa: E402  (deploy/truth_error.py)

CLUSTER_FILE = """# Written by bench/tune.py for one measured run.
[cluster]
scene = {scene}
duration = {seconds}
truth_every = {truth_every}
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


class RunError(RuntimeError):
    pass


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


def figures_of(run):
    """The budget's metrics (tuning/budget.py) from a finished run folder."""
    report = json.loads((run / "report.json").read_text())
    clients = report["clients"]
    if not clients:
        raise RunError(f"{run}: no player finished the run")
    errors, _, _ = truth_error.join(run)
    shown = [e for per_order in errors.values() for e in per_order]
    if not shown:
        raise RunError(f"{run}: no shown sample met a truth sample (truth_every too sparse?)")
    return {"shown_error_p99": percentile(shown, 99),
            "kbps_per_client": steady_kbps(run) or
            sum(c["bytes_in_per_s"] for c in clients) * 8 / 1000 / len(clients),
            "tick_ms_p99": max(z["tick_ms_p99"] for z in report["zones"]),
            "samples": len(shown)}


def run_once(overlay, folder, ranks, seconds, players, truth_every, bin_dir):
    """Runs the overlay's scene; returns its figures. Raises RunError with the cluster's words."""
    folder.mkdir(parents=True, exist_ok=True)
    cluster = folder / "tune.cluster"
    cluster.write_text(CLUSTER_FILE.format(scene=overlay, seconds=seconds, truth_every=truth_every,
                                           ranks=ranks, players=players))
    run = folder / "run"
    env = dict(os.environ, ZONESIM_BIN=str(bin_dir))
    with open(folder / "cluster.log", "w") as out:
        p = subprocess.run(["bash", ROOT / "deploy" / "cluster.sh", cluster, run], stdout=out,
                           stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    if p.returncode != 0:
        tail = (folder / "cluster.log").read_text(errors="replace").strip().splitlines()[-6:]
        raise RunError(f"the run of {overlay} failed (exit {p.returncode}; {folder / 'cluster.log'}):\n    "
                       + "\n    ".join(tail))
    return figures_of(run)
