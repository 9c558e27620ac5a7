#!/usr/bin/python3
"""How many players one gateway serves at 30 Hz on one core: a zone rank, a gateway and a
client_stub fleet of N players on this machine for each N; prints the gateway's own tick time
(everything it does per 33 ms tick: DDS takes, interest, per-player diffs, packing, sends),
its traffic per player and the linear extrapolation of N to a full 33 ms tick.
Usage: bench/net/gateway_capacity.py [N ...]   (ZONESIM_BIN: the build's bin/ directory)"""
import json
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "integration"))
import harness as h  # noqa: E402

SCENE = Path(__file__).resolve().parent / "capacity.yaml"
SECONDS = 8
counts = [int(a) for a in sys.argv[1:]] or [25, 50, 100, 200]
print(f"{'players':>7} {'tick ms mean':>12} {'tick ms max':>11} {'kbit/s out per player':>21} "
      f"{'welcomed':>8} {'players at 33 ms (linear)':>25}")
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
                      100000], out / "gateway.log", env)
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
        mean = g["tick_ms_mean"]
        print(f"{n:>7} {mean:>12.2f} {g['tick_ms_max']:>11.1f} {per_player:>21.1f} {welcomed:>8} "
              f"{n * 33.3 / mean if mean > 0 else 0:>25.0f}", flush=True)
