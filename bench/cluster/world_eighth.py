#!/usr/bin/python3
"""The world at 1/8 scale: scenes/world_eighth.yaml on bench/cluster/world_eighth.cluster (8 zone
ranks, two gateways behind a lobby, 312 players, 875 NPCs with AI, 12,500 rigid bodies), run
through deploy/cluster.sh, then the figures a zone cluster is judged by:
  - each rank's tick p50/p99 (and its entities, awake bodies, agents);
  - per-client downlink kbit/s (UDP payload, gateway to player) p50/p99 over players, and the
    gateways' worst second of any player;
  - the error players were shown against the zones' truth, by distance band, p50/p99;
  - handoff latency p50/p99 over every rank's timed handoffs;
  - inputs sent, applied, lost and duplicated;
  - per player kind (walkers, riders, flyers): players, kbit/s received, error, entities in view.
On fewer cores than processes the ranks are oversubscribed, and the table says so: tick times
then include waiting for a core.
Usage: bench/cluster/world_eighth.py [RUN_DIR]
  (environment: ZONESIM_BIN, the build's bin/ folder, default build/bin; ZONESIM_WORLD_SECONDS,
   default 60; ZONESIM_WORLD_PLAYERS, default 312; ZONESIM_WORLD_GATEWAY_ARGS)
Writes RUN_DIR/world_eighth.json beside the run's own report.json."""
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "deploy"))
from report import load  # noqa: E402  (deploy/report.py)
from truth_error import pct  # noqa: E402  (deploy/truth_error.py)

CLUSTER = ROOT / "bench" / "cluster" / "world_eighth.cluster"
PROCESSES_BESIDE_ZONES = 4  # two gateways, the lobby, the fleet


def run_cluster(run_dir):
    env = dict(os.environ)
    env.setdefault("ZONESIM_BIN", str(ROOT / "build" / "bin"))
    log = run_dir.parent / (run_dir.name + "-cluster.log")
    print(f"running {CLUSTER.relative_to(ROOT)} into {run_dir} (log: {log})", flush=True)
    with open(log, "w") as out:
        p = subprocess.Popen(["bash", str(ROOT / "deploy" / "cluster.sh"), str(CLUSTER),
                              str(run_dir)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True, env=env, cwd=ROOT)
        for line in p.stdout:
            out.write(line)
            # The launcher's progress lines, so a long run shows it is alive.
            if line.startswith("==") or line.lstrip().startswith("t="):
                print("  " + line.rstrip(), flush=True)
        if p.wait() != 0:
            sys.exit(f"world_eighth: the cluster run failed (exit {p.returncode}); see {log}")


def figures(run_dir):
    zones = [load(f) for f in sorted(run_dir.glob("zone_*_summary.json"),
                                     key=lambda f: int(f.stem.split("_")[1]))]
    gateways = [load(f) for f in sorted(run_dir.glob("gateway-*/gateway_summary.json"))]
    clients = load(run_dir / "clients_summary.json")
    report = load(run_dir / "report.json")
    cores = os.cpu_count() or 1
    processes = len(zones) + PROCESSES_BESIDE_ZONES
    players = [p for g in gateways for p in g["players"] if p["seconds"] > 0]
    kbps = [p["bytes_out_per_s"] * 8 / 1000 for p in players]
    handoff_ms = [v for z in zones for v in z.get("handoff_latency_ms", [])]
    sent = clients["totals"]["inputs"]
    applied = sum(z["inputs_applied"] for z in zones)
    return {
        "ranks": len(zones),
        "cores": cores,
        "processes": processes,
        "oversubscribed": processes > cores,
        "entities": sum(z["entities_end"] for z in zones),
        "agents": sum(z["agents"] for z in zones),
        "bodies_awake": sum(z["bodies_awake"] for z in zones),
        "zone_ticks": [{"rank": z["rank"], "ticks": z["ticks"], "p50_ms": z["tick_ms_p50"],
                        "p99_ms": z["tick_ms_p99"], "entities": z["entities_end"],
                        "bodies_awake": z["bodies_awake"], "agents": z["agents"]} for z in zones],
        "players": len(players),
        "players_per_gateway": [len(g["players"]) for g in gateways],
        "gateway_tick_ms_mean": [g["tick_ms_mean"] for g in gateways],
        "gateway_tick_cpu_ms_mean": [g.get("tick_cpu_ms_mean", float("nan")) for g in gateways],
        "client_kbps_p50": pct(kbps, 50),
        "client_kbps_p99": pct(kbps, 99),
        "client_kbps_worst_second": max(g["client_kbps_max"] for g in gateways),
        "error_bands": report["truth_error"]["bands"],
        "error_orders": report["truth_error"]["orders"],
        "handoffs": len(handoff_ms),
        "handoff_ms_p50": pct(handoff_ms, 50),
        "handoff_ms_p99": pct(handoff_ms, 99),
        "inputs_sent": sent,
        "inputs_applied": applied,
        "inputs_lost": sent - applied,
        "inputs_skipped_as_gaps": sum(z["inputs_skipped"] for z in zones),
        "inputs_unroutable": sum(z["inputs_unroutable"] for z in zones),
        "inputs_duplicates_dropped": sum(z["inputs_duplicate"] for z in zones),
        "kinds": clients.get("kinds", {}),
    }


def print_figures(f):
    over = (f"OVERSUBSCRIBED: {f['processes']} processes on {f['cores']} cores; tick times "
            "include waiting for a core") if f["oversubscribed"] else \
        f"{f['processes']} processes on {f['cores']} cores"
    print(f"\n== world at 1/8 scale: {f['ranks']} zone ranks, {f['players']} players over "
          f"{len(f['players_per_gateway'])} gateways {f['players_per_gateway']}, "
          f"{f['entities']} entities ({f['agents']} AI agents, {f['bodies_awake']} bodies awake "
          f"at the end)\n== {over}")
    print(f"{'rank':>4} {'ticks':>6} {'tick p50 ms':>11} {'p99 ms':>8} {'entities':>8} "
          f"{'awake':>6} {'agents':>6}")
    for z in f["zone_ticks"]:
        print(f"{z['rank']:>4} {z['ticks']:>6} {z['p50_ms']:>11.2f} {z['p99_ms']:>8.2f} "
              f"{z['entities']:>8} {z['bodies_awake']:>6} {z['agents']:>6}")
    print("gateway tick ms mean " + ", ".join(f"{v:.1f}" for v in f["gateway_tick_ms_mean"]) +
          "; its own CPU per tick " + ", ".join(f"{v:.1f}" for v in f["gateway_tick_cpu_ms_mean"]))
    print(f"per-client downlink: p50 {f['client_kbps_p50']:.1f} kbit/s, p99 "
          f"{f['client_kbps_p99']:.1f} kbit/s (worst second of any player "
          f"{f['client_kbps_worst_second']:.1f})")
    print(f"{'error shown':>12} {'samples':>9} {'p50 m':>8} {'p99 m':>8}")
    for band in ("0-25 m", "25-50 m", "50-100 m", "100+ m"):
        b = f["error_bands"].get(band)
        if b:
            print(f"{band:>12} {b['samples']:>9} {b['p50_m']:>8.3f} {b['p99_m']:>8.3f}")
    print(f"handoffs {f['handoffs']}: latency p50 {f['handoff_ms_p50']:.0f} ms, p99 "
          f"{f['handoff_ms_p99']:.0f} ms")
    print(f"inputs: {f['inputs_sent']} sent, {f['inputs_applied']} applied, {f['inputs_lost']} "
          f"lost ({f['inputs_skipped_as_gaps']} skipped as gaps, {f['inputs_unroutable']} "
          f"unroutable), {f['inputs_duplicates_dropped']} duplicates arrived and were dropped")
    if f["kinds"]:
        # The correction error: how far a shown entity jumps when its next state arrives.
        print(f"{'kind':>8} {'players':>7} {'kbit/s p50':>10} {'max':>6} {'correction p50 m':>16} "
              f"{'p99 m':>6} {'in view':>7}")
        for name, k in f["kinds"].items():
            print(f"{name:>8} {k['players']:>7} {k['kbps_in_p50']:>10.1f} {k['kbps_in_max']:>6.1f} "
                  f"{k['dr_error_m_p50']:>16.3f} {k['dr_error_m_p99']:>6.3f} "
                  f"{k['visible_entities_mean']:>7.1f}")


def main():
    run_dir = Path(sys.argv[1]) if len(sys.argv) > 1 else \
        ROOT / "runs" / time.strftime("world_eighth-%Y%m%d-%H%M%S")
    run_dir = run_dir.resolve()
    run_cluster(run_dir)
    f = figures(run_dir)
    (run_dir / "world_eighth.json").write_text(json.dumps(f, indent=1) + "\n")
    print_figures(f)
    print(f"\nfigures written to {run_dir / 'world_eighth.json'}")


if __name__ == "__main__":
    main()
