"""Transport reliability under 10% injected loss both ways (gateway -> client and back).

One zone cluster, two gateways on it: one resends unacknowledged spawns, states and despawns
(the default), the other does not (--no-resend). Each serves its own players through a lossy
link. With resend, the correction clients see at each update (how far what they showed was
from the newest state) stays within ERROR_BOUND_M at p99, no entity the gateway keeps updating
is missing a spawn, and no despawned entity lingers as a ghost. The run without resend is
printed alongside for comparison (its figures are reported, not asserted)."""
import json
import tempfile
import time
from pathlib import Path

import harness as h

SCENE = h.SOURCE_DIR / "scenes/test_e2e.yaml"
CLIENT_SECONDS = 14  # > heartbeat (5 s) + 1 s, so a lost despawn shows as a ghost
PLAYERS = 8
LOSS = 0.10
# The scene's position threshold is 0.5 m; a lost update costs one resend timeout (~RTT plus
# the 50 ms between acks) of extra drift for walkers (<= 2.5 m/s) and players (12 m/s).
ERROR_BOUND_M = 3.0


def wait_port(path):
    for _ in range(100):
        if path.exists() and path.read_text().strip():
            return path.read_text().strip()
        time.sleep(0.1)
    h.fail(f"no port in {path}")


with tempfile.TemporaryDirectory(prefix="zs_lossy_") as tmp:
    out = Path(tmp)
    domain = h.free_dds_domain()
    env = h.base_env()
    zones = h.start(h.mpirun(4, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                             "--realtime", "--dds-domain", domain), out / "zones.log", env)
    variants = {"resend": [], "no_resend": ["--no-resend"]}
    gateways, clients = {}, {}
    for gid, (name, extra) in enumerate(variants.items(), start=1):
        d = out / name
        d.mkdir()
        gateways[name] = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--port", 0,
                                  "--port-file", d / "port", "--dds-domain", domain,
                                  "--gateway-id", gid, "--metrics", d, "--inject-loss", LOSS,
                                  *extra], d / "gateway.log", env)
    ports = {name: wait_port(out / name / "port") for name in variants}
    time.sleep(2)
    for name in variants:
        d = out / name
        clients[name] = h.start([h.bin_dir() / "client_stub", "--scene", SCENE, "--gateway",
                                 f"127.0.0.1:{ports[name]}", "--players", PLAYERS, "--duration",
                                 CLIENT_SECONDS, "--summary", d / "clients.json",
                                 "--inject-loss", LOSS], d / "clients.log", env)
    for name, p in clients.items():
        try:
            rc = p.wait(timeout=60)
        except Exception:
            h.fail(f"client_stub ({name}) did not finish\n{h.tail(out / name / 'clients.log')}")
        h.check(rc == 0, f"client_stub ({name}) exited cleanly")
    time.sleep(1)
    for g in gateways.values():
        h.stop(g)
    h.stop(zones, grace=30)

    fig = {}
    for name in variants:
        s = h.load_json(out / name / "clients.json")
        g = h.load_json(out / name / "gateway_summary.json")
        t, cs = s["totals"], s["clients"]
        fig[name] = {
            "welcomed": sum(1 for c in cs if c.get("avatar_id", 0) != 0),
            "updates": t["updates"],
            "dr_error_m_p50": t["dr_error_m_p50"],
            "dr_error_m_p99": t["dr_error_m_p99"],
            "ghosts": sum(c["ghosts"] for c in cs),
            "unspawned": sum(c["unspawned"] for c in cs),
            "duplicates": t["duplicates"],
            "resent": g.get("resent", 0),
            "kbit_per_s_per_client": t["bytes_in_per_s"] * 8 / 1000 / PLAYERS,
        }
    print(json.dumps(fig, indent=1))
    r, n = fig["resend"], fig["no_resend"]
    h.check(r["welcomed"] == PLAYERS and n["welcomed"] == PLAYERS, "all players welcomed despite loss")
    h.check(r["updates"] > 0 and n["updates"] > 0, "players received updates")
    h.check(r["resent"] > 0, f"the resending gateway resent ({r['resent']})")
    h.check(n["resent"] == 0, "the comparison gateway did not")
    h.check(r["dr_error_m_p99"] <= ERROR_BOUND_M,
            f"p99 correction with resend {r['dr_error_m_p99']:.2f} m <= {ERROR_BOUND_M} m "
            f"(without resend: {n['dr_error_m_p99']:.2f} m)")
    h.check(r["ghosts"] == 0, f"no ghost of a despawned entity with resend (without: {n['ghosts']})")
    h.check(r["unspawned"] == 0, f"no entity left unspawned with resend (without: {n['unspawned']})")
    cost = r["kbit_per_s_per_client"] / max(1e-9, n["kbit_per_s_per_client"])
    print(f"bandwidth per client: {r['kbit_per_s_per_client']:.1f} kbit/s with resend, "
          f"{n['kbit_per_s_per_client']:.1f} without (x{cost:.2f})")
print("lossy transport passed")
