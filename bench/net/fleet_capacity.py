#!/usr/bin/python3
"""What one client_stub costs per player: a zone rank, a gateway and one client_stub with N
players (bench/net/capacity.yaml, as gateway_capacity.py) for each N; prints the players
welcomed, the fleet's CPU per player per second of run, the inputs each player sent per
second (the scene's input rate when the fleet keeps up), and the datagrams the fleet received
per second. The fleet's CPU is measured from outside (the rusage of the reaped client_stub:
start-up and goodbyes included) and, where the binary reports it, by the fleet's own loop.
On a 2-core machine the zone, the gateway and the fleet share the cores, and the gateway does
not keep 30 Hz for 2,000 players (docs/benchmarks.md): the downlink then thins, which the
datagrams per second show. The fleet's own cost per player is the figure this measures.

With --baseline BIN, each N also runs that client_stub (e.g. main's, before the epoll loop),
alternating with this build's, so old and new share the machine's state.
Usage: bench/net/fleet_capacity.py [--baseline BIN] [--seconds S] [--scene FILE] [--link P] [N ...]
(ZONESIM_BIN: the build's bin/ directory)"""
import argparse
import resource
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "integration"))
import harness as h  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("players", type=int, nargs="*", default=[500, 1000, 2000])
parser.add_argument("--baseline", type=Path, help="another client_stub to compare, run alike")
parser.add_argument("--seconds", type=float, default=8)
parser.add_argument("--scene", type=Path, default=Path(__file__).resolve().parent / "capacity.yaml")
parser.add_argument("--link", help="client_stub --link PROFILE for every player (e.g. wifi): "
                    "held datagrams spread the players' due times over the second")
args = parser.parse_args()
NAN = float("nan")


def children_cpu_s():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(client_stub, n):
    """One zone rank, one gateway and client_stub with n players; returns the figures."""
    with tempfile.TemporaryDirectory(prefix="zs_fleet_cap_") as tmp:
        out = Path(tmp)
        domain = h.free_dds_domain()
        env = h.base_env()
        zones = h.start(h.mpirun(1, h.bin_dir() / "zone_node", "--scene", args.scene, "--duration",
                                 600, "--realtime", "--metrics", out, "--dds-domain", domain),
                        out / "zones.log", env)
        gw = h.start([h.bin_dir() / "gateway", "--scene", args.scene, "--port", 0, "--port-file",
                      out / "port", "--dds-domain", domain, "--metrics", out, "--max-sessions",
                      100000], out / "gateway.log", env)
        port = h.wait_for_port(out / "port", gw, out / "gateway.log")
        time.sleep(2)
        # client_stub is the only child reaped in between: the difference is its CPU time.
        before = children_cpu_s()
        h.run([client_stub, "--scene", args.scene, "--gateway", f"127.0.0.1:{port}", "--players",
               n, "--duration", args.seconds, "--summary", out / "clients.json",
               *(["--link", args.link] if args.link else [])],
              out / "clients.log", env, timeout=300)
        outside_cpu = children_cpu_s() - before
        h.stop(gw)
        h.stop(zones, grace=30)
        g = h.load_json(out / "gateway_summary.json")
        c = h.load_json(out / "clients.json")
        t = c["totals"]
        s = c["duration_s"]
        return {
            "welcomed": t["welcomed"],
            "outside_us": outside_cpu * 1e6 / (n * s),
            # A client_stub built before the fleet reported its CPU (a baseline) shows nan.
            "loop_us": c.get("fleet_cpu_us_per_player_s", NAN),
            "wakeups": c.get("fleet_wakeups_per_s", NAN),
            "inputs": t["inputs"] / n / s,
            "datagrams_in": t["datagrams_in_per_s"],
            "gateway_tick_cpu_ms": g.get("tick_cpu_ms_mean", NAN),
        }


binaries = [("new", h.bin_dir() / "client_stub")]
if args.baseline:
    binaries.insert(0, ("baseline", args.baseline))
print(f"scene {args.scene.name}, link {args.link or 'none'}, {args.seconds:g} s per run; "
      "fleet cpu in us per player-second")
print(f"{'client_stub':>11} {'players':>7} {'welcomed':>8} {'fleet cpu (outside)':>19} "
      f"{'fleet cpu (loop)':>16} {'wake-ups/s':>10} {'inputs/player/s':>15} "
      f"{'datagrams in/s':>14} {'gateway tick cpu ms':>19}")
behind = []
for n in args.players:
    for name, binary in binaries:
        r = run(binary, n)
        if r["gateway_tick_cpu_ms"] > 1000 / 30:
            behind.append(f"{name} at {n}")
        print(f"{name:>11} {n:>7} {r['welcomed']:>8} {r['outside_us']:>19.1f} {r['loop_us']:>16.1f} "
              f"{r['wakeups']:>10.0f} {r['inputs']:>15.2f} {r['datagrams_in']:>14.0f} "
              f"{r['gateway_tick_cpu_ms']:>19.2f}", flush=True)
if behind:
    print(f"note: the gateway's tick needed more than its 33 ms of CPU in the runs {', '.join(behind)}"
          " players: it fell behind 30 Hz on this machine and the downlink thinned (datagrams in/s);"
          " the fleet's CPU per player is still its own, the figure this measures")
