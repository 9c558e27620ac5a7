"""Zones, a gateway and a client_stub for a few seconds: players get welcomed, receive updates,
and at least one avatar changes zone, with the handoff seen by zones and clients alike.
With the argument `balancing`, the zones also move their boundaries every 15 ticks (any
imbalance at all starts a move), so handoff and interest must keep working while they move."""
import sys
import tempfile
import time
from pathlib import Path

import harness as h

SCENE = h.SOURCE_DIR / "scenes/test_e2e.yaml"
CLIENT_SECONDS = 8
BALANCING = "balancing" in sys.argv[1:]

with tempfile.TemporaryDirectory(prefix="zs_e2e_") as tmp:
    out = Path(tmp)
    domain = h.free_dds_domain()
    env = h.base_env()
    # The zones run until stopped: on a slow machine a fixed duration could end them before the
    # players' goodbyes (and the avatars' removal) went through.
    balance = ["--balance-every", 15, "--balance-threshold", 1.0] if BALANCING else []
    zones = h.start(h.mpirun(4, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                             "--realtime", "--metrics", out, "--dds-domain", domain, *balance),
                    out / "zones.log", env)
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--bind", "127.0.0.1", "--port", 0,
                       "--port-file", out / "port",
                       "--dds-domain", domain, "--metrics", out], out / "gateway.log", env)
    port = h.wait_for_port(out / "port", gateway, out / "gateway.log")
    time.sleep(2)
    h.run([h.bin_dir() / "client_stub", "--scene", SCENE, "--gateway", f"localhost:{port}", "--players", 12,
           "--duration", CLIENT_SECONDS, "--summary", out / "clients.json", "--metrics", out],
          out / "clients.log", env, timeout=60)
    time.sleep(2)  # 60 ticks for the last despawn requests to reach the zones
    h.stop(gateway)
    # SIGTERM: the ranks finish their tick and write their summaries (mpirun itself then
    # reports the signal in its exit status, so the summaries are what is checked).
    h.stop(zones, grace=30)
    if not all((out / f"zone_{r}_summary.json").exists() for r in range(4)):
        h.fail("zones did not write their summaries\n%s" % h.tail(out / "zones.log"))

    h.check(f"gateway listening on 127.0.0.1:{port}" in (out / "gateway.log").read_text(),
            "the gateway named the address it bound; players reached it by name (localhost)")
    clients = h.load_json(out / "clients.json")["clients"]
    zone_summaries = [h.load_json(out / f"zone_{r}_summary.json") for r in range(4)]
    h.check(len(clients) == 12, "12 players reported")
    welcomed = [c for c in clients if c.get("avatar_id", 0) != 0]
    h.check(len(welcomed) == 12, f"every player was welcomed with an avatar ({len(welcomed)})")
    h.check(all(c["updates_per_s"] > 0 for c in clients), "every player received entity updates")
    h.check(all(c["bytes_in_per_s"] > 0 and c["bytes_out_per_s"] > 0 for c in clients), "traffic both ways")
    handoffs = sum(z["handoffs_in"] for z in zone_summaries)
    h.check(handoffs >= 1, f"at least one avatar changed zone ({handoffs})")
    h.check(sum(c.get("handoffs", 0) for c in clients) >= 1, "clients were told of a handoff")
    h.check(sum(z["inputs_applied"] for z in zone_summaries) > 0, "zones applied player inputs")
    if BALANCING:
        moves = max(z["rebalances"] for z in zone_summaries)
        h.check(moves >= 3, f"the zone boundaries moved while players played ({moves} times)")
    skipped = sum(z.get("inputs_skipped", 0) for z in zone_summaries)
    h.check(skipped == 0, f"no input sequence number was skipped across handoffs ({skipped})")
    # Every input the gateway forwarded was applied exactly once, or reached its zone after the
    # player left (unroutable): none lost or applied twice across the handoffs.
    forwarded = h.load_json(out / "gateway_summary.json")["inputs_forwarded"]
    applied = sum(z["inputs_applied"] for z in zone_summaries)
    unroutable = sum(z.get("inputs_unroutable", 0) for z in zone_summaries)
    h.check(applied + unroutable == forwarded,
            f"inputs applied {applied} + after the player left {unroutable} == forwarded {forwarded}")
    timed = sum(z.get("handoffs_timed", 0) for z in zone_summaries)
    h.check(timed >= 1, f"handoffs were followed by inputs applied at the new owner ({timed})")
    h.check(sum(z["conservation_failures"] for z in zone_summaries) == 0, "nothing lost or doubled")
    spawned = sum(z["avatars_spawned"] for z in zone_summaries)
    destroyed = sum(z["entities_destroyed"] for z in zone_summaries)
    h.check(spawned == 12 and destroyed == 12, f"12 avatars created and removed when players left ({spawned}, {destroyed})")
    h.check(sum(z["entities_start"] for z in zone_summaries) == sum(z["entities_end"] for z in zone_summaries),
            "the world ends with the entities it started with")
print("end-to-end passed")
