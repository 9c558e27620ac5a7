#!/usr/bin/python3
"""How many players one gateway serves at 30 Hz on one core: a zone rank, a gateway and a
client_stub fleet of N players on this machine for each N; prints the gateway's own tick time
(everything it does per 33 ms tick: DDS takes, interest, per-player diffs, packing, sends) as
wall time and as the gateway thread's own CPU time (the fleet and the zone share the machine:
wall time grows with their load, CPU time does not), the whole gateway process's CPU per tick
(receiving inputs, DDS threads too), its traffic per player and the linear extrapolation of N
to a full 33 ms tick of the gateway thread's CPU; beside them, the client_stub fleet's own CPU
per player per second (bench/net/fleet_capacity.py measures that one further). With a scene of
several player kinds (clients.kinds, e.g. --scene scenes/player_kinds.yaml) each N gets a line per
kind too: its players, kbit/s received p50/max, correction error p50/p99/max and entities in view.
Usage: bench/net/gateway_capacity.py [--scene SCENE] [N ...]   (ZONESIM_BIN: the build's bin/;
ZONESIM_CAPACITY_GATEWAY_ARGS: more gateway options, e.g. "--full-scan-every 1" to compare)"""
import argparse
import json
import os
import shlex
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "integration"))
import harness as h  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--scene", type=Path, default=Path(__file__).resolve().parent / "capacity.yaml")
parser.add_argument("counts", type=int, nargs="*", default=[25, 50, 100, 200])
args = parser.parse_args()
SCENE = args.scene.resolve()
SECONDS = 8
counts = args.counts


def print_kinds(kinds, sessions):
    """One line per kind when the fleet mixed several (a fleet from before kinds has none)."""
    if len(kinds) < 2:
        return
    for name, k in kinds.items():
        print(f"{'':>7} {name:>6}: {k['players']} players ({sessions.get(name, 0)} sessions), "
              f"kbit/s in p50 {k['kbps_in_p50']:.1f} max {k['kbps_in_max']:.1f}, error m p50 "
              f"{k['dr_error_m_p50']:.3f} p99 {k['dr_error_m_p99']:.3f} max {k['dr_error_m_max']:.3f}, "
              f"in view {k['visible_entities_mean']:.1f}", flush=True)

print(f"{'players':>7} {'tick ms mean':>12} {'tick ms max':>11} {'tick cpu ms':>11} "
      f"{'process cpu ms':>14} {'kbit/s out per player':>21} {'welcomed':>8} "
      f"{'players at 33 ms cpu (linear)':>29} {'fleet cpu us/player-s':>21}")
for n in counts:
    with tempfile.TemporaryDirectory(prefix="zs_cap_") as tmp:
        out = Path(tmp)
        domain = h.free_dds_domain()
        env = h.base_env()
        zones = h.start(h.mpirun(1, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                                 "--realtime", "--metrics", out, "--dds-domain", domain),
                        out / "zones.log", env)
        gw = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--port", 0, "--port-file",
                      out / "port", "--dds-domain", domain, "--metrics", out, "--max-sessions",
                      100000, "--expect-zones", 1,  # one rank, any scene
                      *shlex.split(os.environ.get("ZONESIM_CAPACITY_GATEWAY_ARGS", ""))],
                     out / "gateway.log", env)
        port = h.wait_for_port(out / "port", gw, out / "gateway.log")
        time.sleep(2)
        h.run([h.bin_dir() / "client_stub", "--scene", SCENE, "--gateway", f"127.0.0.1:{port}",
               "--players", n, "--duration", SECONDS, "--summary", out / "clients.json"],
              out / "clients.log", env, timeout=120)
        h.stop(gw)
        h.stop(zones, grace=30)
        g = h.load_json(out / "gateway_summary.json")
        c = h.load_json(out / "clients.json")
        welcomed = sum(1 for p in c["clients"] if p.get("avatar_id", 0) != 0)
        per_player = g["bytes_out"] * 8 / 1000 / max(1, n) / g["t"]
        # A gateway built before CPU time was reported (for A/B runs) shows nan there.
        cpu = g.get("tick_cpu_ms_mean", float("nan"))
        print(f"{n:>7} {g['tick_ms_mean']:>12.2f} {g['tick_ms_max']:>11.1f} {cpu:>11.2f} "
              f"{g.get('process_cpu_ms_per_tick', float('nan')):>14.2f} {per_player:>21.1f} "
              f"{welcomed:>8} {n * 33.3 / cpu if cpu > 0 else 0:>29.0f} "
              f"{c.get('fleet_cpu_us_per_player_s', float('nan')):>21.1f}", flush=True)
        print_kinds(c.get("kinds", {}), g.get("sessions_by_kind", {}))
