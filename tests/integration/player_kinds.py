"""Player kinds end to end (scenes/player_kinds.yaml): 2 zone ranks, a gateway and a fleet of
12 players mixed by the scene's shares (6 walkers, 3 riders, 3 flyers), beside a second fleet
forced to one kind (client_stub --kind rider). Checked from the summaries: each kind has its
expected count at the clients and at the gateway, flyers see more entities on average than
walkers (their nimbus is 160 m, the walkers' about 60 m), flyers show their own avatar at the
flyer height and walkers on the ground, also after crossing the zone border, and every avatar
was made and removed. A kind the scene does not list is refused by client_stub by name."""
import subprocess
import tempfile
import time
from pathlib import Path

import harness as h

SCENE = h.SOURCE_DIR / "scenes/player_kinds.yaml"
CLIENT_SECONDS = 20  # long enough that some flyer crosses the border (each flies ~3 legs)
FLYER_HEIGHT = 60  # the scene's flyer height; the ground is y = 0
# States reach the client quantised (1/512 m) and it shows them extrapolated: a flyer's y is
# held exactly by the zone, so anything beyond rounding means it climbed or sank.
HEIGHT_SLACK_M = 0.05
EXPECTED = {"walker": 6, "rider": 3, "flyer": 3}
FORCED_RIDERS = 2


def by_kind(clients, kind):
    return [c for c in clients if c["kind"] == kind]


with tempfile.TemporaryDirectory(prefix="zs_kinds_") as tmp:
    out = Path(tmp)
    env = h.base_env()
    client = [h.bin_dir() / "client_stub", "--scene", SCENE]
    bad = subprocess.run(list(map(str, client + ["--gateway", "127.0.0.1:9", "--kind", "plane"])),
                         capture_output=True, text=True, env=env, timeout=60)
    h.check(bad.returncode != 0 and "--kind: 'plane' is not a kind of the scene (its kinds: "
            "walker, rider, flyer)" in bad.stderr, f"an unknown --kind is refused by name ({bad.stderr.strip()})")

    domain = h.free_dds_domain()
    zones = h.start(h.mpirun(2, h.bin_dir() / "zone_node", "--scene", SCENE, "--duration", 600,
                             "--realtime", "--metrics", out, "--dds-domain", domain),
                    out / "zones.log", env)
    gateway = h.start([h.bin_dir() / "gateway", "--scene", SCENE, "--port", 0, "--port-file",
                       out / "port", "--dds-domain", domain, "--metrics", out], out / "gateway.log", env)
    port = h.wait_for_port(out / "port", gateway, out / "gateway.log")
    time.sleep(2)
    target = ["--gateway", f"127.0.0.1:{port}", "--duration", CLIENT_SECONDS]
    forced = h.start(client + target + ["--players", FORCED_RIDERS, "--kind", "rider", "--seed", 2,
                                        "--summary", out / "riders.json"], out / "riders.log", env)
    h.run(client + target + ["--summary", out / "clients.json"], out / "clients.log", env,
          timeout=120)
    if forced.wait(timeout=60) != 0:
        h.fail(f"the forced-kind fleet failed\n{h.tail(out / 'riders.log')}")
    time.sleep(2)  # for the last despawn requests to reach the zones
    h.stop(gateway)
    h.stop(zones, grace=30)
    if not all((out / f"zone_{r}_summary.json").exists() for r in range(2)):
        h.fail("zones did not write their summaries\n%s" % h.tail(out / "zones.log"))

    summary = h.load_json(out / "clients.json")
    clients = summary["clients"]
    kinds = summary["kinds"]
    riders = h.load_json(out / "riders.json")
    gw = h.load_json(out / "gateway_summary.json")
    zone_summaries = [h.load_json(out / f"zone_{r}_summary.json") for r in range(2)]

    for kind, n in EXPECTED.items():
        h.check(len(by_kind(clients, kind)) == n and kinds[kind]["players"] == n,
                f"{n} {kind}s in the mixed fleet ({len(by_kind(clients, kind))}, summary {kinds[kind]['players']})")
    h.check(all(c["avatar_id"] != 0 for c in clients + riders["clients"]), "every player was welcomed")
    h.check([c["kind"] for c in riders["clients"]] == ["rider"] * FORCED_RIDERS
            and list(riders["kinds"]) == ["rider"], "--kind rider made every player of that fleet a rider")
    sessions = gw["sessions_by_kind"]
    h.check(sessions == {"walker": 6, "rider": 3 + FORCED_RIDERS, "flyer": 3},
            f"the gateway counted its sessions by kind ({sessions})")
    h.check(gw["dropped"]["unknown_kind"] == 0, "no Hello was refused for its kind")

    seen = {k: kinds[k]["visible_entities_mean"] for k in EXPECTED}
    print("visible entities (time-averaged, mean per kind): "
          + ", ".join(f"{k} {v:.1f}" for k, v in seen.items()))
    h.check(seen["flyer"] > 2 * seen["walker"],
            f"flyers see more than twice what walkers see ({seen['flyer']:.1f} vs {seen['walker']:.1f})")
    h.check(seen["rider"] > seen["walker"], "riders see more than walkers")
    for kind, want in (("flyer", FLYER_HEIGHT), ("walker", 0), ("rider", 0)):
        ys = [c.get("avatar_y") for c in by_kind(clients, kind)]
        h.check(all(y is not None and abs(y - want) <= HEIGHT_SLACK_M for y in ys),
                f"{kind}s show their avatars at y = {want} ({ys})")
    flyer_handoffs = sum(c["handoffs"] for c in by_kind(clients, "flyer"))
    print(f"handoffs seen by flyers: {flyer_handoffs}; "
          f"by all players: {sum(c['handoffs'] for c in clients)}")
    h.check(flyer_handoffs >= 1, "a flyer crossed the zone border (and still shows its height)")
    for k in EXPECTED:
        print(f"{k}: kbit/s in p50 {kinds[k]['kbps_in_p50']:.1f} max {kinds[k]['kbps_in_max']:.1f}, "
              f"error m p50 {kinds[k]['dr_error_m_p50']:.3f} p99 {kinds[k]['dr_error_m_p99']:.3f} "
              f"max {kinds[k]['dr_error_m_max']:.3f}")
    h.check(kinds["flyer"]["kbps_in_p50"] > kinds["walker"]["kbps_in_p50"],
            "flyers receive more than walkers (they are sent more entities)")

    players = len(clients) + FORCED_RIDERS
    spawned = sum(z["avatars_spawned"] for z in zone_summaries)
    refused = sum(z.get("avatars_refused", 0) for z in zone_summaries)
    destroyed = sum(z["entities_destroyed"] for z in zone_summaries)
    h.check(spawned == players and refused == 0 and destroyed == players,
            f"{players} avatars made and removed, none refused ({spawned}, {refused}, {destroyed})")
    h.check(sum(z["conservation_failures"] for z in zone_summaries) == 0, "nothing lost or doubled")
print("player kinds passed")
